#pragma once
// Dense BEM influence matrices H and G of eq. (1), H U = G T, for linear triangles with nodal
// collocation: unknowns are the displacement and traction at each vertex (3 components each).

#include <Eigen/Core>
#include <functional>

#include "physics/bem/bem_material.h"
#include "physics/mesh/triangle_mesh.h"

namespace vesica::physics {

struct BemMatrices {
  Eigen::MatrixXd H;  ///< 3#V x 3#V, dimensionless; rows = collocation node, cols = node dof
  Eigen::MatrixXd G;  ///< 3#V x 3#V, m/Pa (m^3/N)
};

struct BemQuadratureOptions {
  int duffy_order = 6;          ///< Gauss-Legendre points per direction on singular elements
  double near_ratio = 1.0;      ///< subdivide a (sub)triangle closer than this x its size
  double far_ratio = 3.0;       ///< beyond this x size the 3-point rule suffices, else 7-point
  int max_subdivision = 2;      ///< levels of 4-way subdivision for near-singular elements
};

/// Assembles H and G on a closed, outward-oriented surface (checked by the caller): regular
/// Gauss quadrature away from the collocation point (subdivided when near), Duffy quadrature on
/// the elements touching it, and the rigid-body identity H_ii = -sum_{j != i} H_ij for the
/// diagonal blocks, so the strongly singular integral is never evaluated. Uses all cores.
/// `on_progress` (optional) is called on the calling thread with the fraction of rows done, in
/// steps of about 5 %, the last time with 1.
BemMatrices AssembleBemMatrices(const TriangleMesh& surface, const ElasticMaterial& material,
                                const BemQuadratureOptions& options = {},
                                const std::function<void(double)>& on_progress = {});

}  // namespace vesica::physics
