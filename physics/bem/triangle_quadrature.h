#pragma once
// Quadrature rules on a triangle in barycentric coordinates. Every rule integrates over the
// triangle as  int_T f dA = area * sum_k weight_k f(point_k), so the weights sum to 1.

#include <array>
#include <vector>

namespace vesica::physics {

struct TriangleQuadraturePoint {
  std::array<double, 3> barycentric;  ///< weights of corners 0, 1, 2 (sum 1)
  double weight;                      ///< fraction of the area (sum over a rule = 1)
};
using TriangleQuadrature = std::vector<TriangleQuadraturePoint>;

/// Gauss-Legendre nodes and weights on [0, 1] with `order` points (exact to degree 2 order - 1).
std::vector<std::array<double, 2>> GaussLegendreUnitInterval(int order);

/// Dunavant's symmetric rules: 3 points (degree 2) and 7 points (degree 5).
const TriangleQuadrature& TriangleGauss3();
const TriangleQuadrature& TriangleGauss7();

/// Duffy rule for an integrand with a 1/r singularity at corner `singular_corner`: the triangle
/// is the image of the unit square collapsed at that corner, whose Jacobian (proportional to the
/// distance) cancels the singularity; `order` x `order` Gauss-Legendre points.
TriangleQuadrature TriangleDuffy(int singular_corner, int order);

}  // namespace vesica::physics
