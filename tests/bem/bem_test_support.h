#pragma once
// Shared fixtures of the BEM tests: a liver-sized ellipsoid with a fixed cap, and a direct
// (non-capacitance) solve of any mix of boundary conditions as the independent reference.

#include <Eigen/LU>
#include <vector>

#include "physics/bem/bem_matrices.h"
#include "physics/bem/ellipsoid_surface.h"

namespace vesica::physics::testing {

/// Ellipsoid 0.10 x 0.07 x 0.04 m (liver-sized) whose vertices with x < -0.06 m are fixed.
inline TriangleMesh LiverLikeEllipsoid(int num_vertices) {
  TriangleMesh mesh = MakeEllipsoidSurface({0.10, 0.07, 0.04}, num_vertices);
  for (int i = 0; i < mesh.num_vertices(); ++i)
    mesh.vertex_labels(i) = mesh.vertices(i, 0) < -0.06 ? kLabelFixed : kLabelNone;
  return mesh;
}

enum class NodeCondition { kDisplacement, kTraction };

/// Solves H U = G T directly for a per-node choice of which of u / t is known (`known` rows hold
/// the known value). Returns (U, T) as #V x 3.
inline std::pair<Vertices, Vertices> DirectBemSolve(const BemMatrices& m,
                                                    const std::vector<NodeCondition>& condition,
                                                    const Vertices& known) {
  const Eigen::Index n = static_cast<Eigen::Index>(condition.size());
  Eigen::MatrixXd a(3 * n, 3 * n);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(3 * n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const Eigen::Vector3d value = known.row(j).transpose();
    if (condition[static_cast<std::size_t>(j)] == NodeCondition::kDisplacement) {
      a.middleCols<3>(3 * j) = -m.G.middleCols<3>(3 * j);  // unknown traction
      rhs -= m.H.middleCols<3>(3 * j) * value;
    } else {
      a.middleCols<3>(3 * j) = m.H.middleCols<3>(3 * j);  // unknown displacement
      rhs += m.G.middleCols<3>(3 * j) * value;
    }
  }
  const Eigen::VectorXd y = a.partialPivLu().solve(rhs);
  Vertices u(n, 3), t(n, 3);
  for (Eigen::Index j = 0; j < n; ++j) {
    if (condition[static_cast<std::size_t>(j)] == NodeCondition::kDisplacement) {
      u.row(j) = known.row(j);
      t.row(j) = y.segment<3>(3 * j).transpose();
    } else {
      u.row(j) = y.segment<3>(3 * j).transpose();
      t.row(j) = known.row(j);
    }
  }
  return {u, t};
}

}  // namespace vesica::physics::testing
