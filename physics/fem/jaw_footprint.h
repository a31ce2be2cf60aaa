#pragma once
// A grasper's jaw as a rectangle on the body's surface, and the consistent nodal weights of loads
// or constraints spread over it (issue 37): for each boundary node i the integrals of its hat
// function N_i over the part of the surface inside the rectangle, times 1, xi and eta (the jaw's
// own coordinates), so a traction t(xi, eta) = t0 + t_xi xi + t_eta eta over the jaw's physical
// footprint becomes nodal forces f_i = t0 m0_i + t_xi m_xi_i + t_eta m_eta_i whatever the mesh,
// instead of "the nodes that fall inside" (1, 4 or 10 of them on the trainer's gallbladders).
//
// The footprint is the surface's part whose projection on the jaw's plane lies in the rectangle
// (each boundary triangle clipped in the plane's coordinates, its area taken on the triangle),
// on the jaw's side: triangles whose centroid lies more than max_depth_m behind the jaw's plane,
// or whose plane is nearly edge-on to it, are not part of it (the body's far side).

#include <Eigen/Core>
#include <vector>

#include "physics/fem/quadratic_tet_mesh.h"
#include "physics/mesh/mesh_topology.h"

namespace vesica::physics {

struct RectangularFootprint {
  Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();     ///< unit, out of the body
  Eigen::Vector3d long_axis = Eigen::Vector3d::UnitX();  ///< unit, perpendicular to normal (xi)
  double length_m = 0.010;                               ///< along long_axis, > 0
  double width_m = 0.005;                                ///< along normal x long_axis (eta), > 0
  /// Surface this far behind the centre is not under the jaw (the far side), > 0.
  double max_depth_m = 0.004;
};

struct FootprintWeights {
  std::vector<int> nodes;  ///< volume nodes whose hat function reaches into the footprint
  /// One row per entry of nodes: integral over the footprint of N_i, xi N_i, eta N_i (m^2, m^3, m^3),
  /// xi and eta measured from the centre along long_axis and normal x long_axis.
  Eigen::MatrixX3d moments;
  double area_m2 = 0;  ///< the footprint's area on the surface (the sum of the first column)
};

/// Throws std::invalid_argument naming the field when the footprint's sizes are not positive and
/// finite or its axes are not unit and perpendicular, or when no surface lies under it.
FootprintWeights ComputeFootprintWeights(const TetBoundary& boundary, const RectangularFootprint& jaw);

/// The same for 10-node tets on the boundary's mesh (quadratic_tet_mesh.h): nodes are the corners
/// and edge midpoints of the 6-node boundary triangles, the rows the integrals of their quadratic
/// shape functions (which, unlike the linear hats, are negative near the corners).
FootprintWeights ComputeQuadraticFootprintWeights(const TetBoundary& boundary, const QuadraticTetMesh& mesh,
                                                  const RectangularFootprint& jaw);

}  // namespace vesica::physics
