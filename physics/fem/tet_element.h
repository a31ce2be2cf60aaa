#pragma once
// Rest-state data of one linear tetrahedron: shape-function gradients and volume, from which the
// 12x12 Hooke stiffness is rebuilt block by block (cheaper to recompute than to store 1 kB/tet).

#include <array>

#include <Eigen/Core>

namespace vesica::physics {

struct TetElement {
  std::array<Eigen::Vector3d, 4> shape_gradients;  ///< grad N_a in the rest frame, 1/m
  Eigen::Matrix3d rest_shape_inverse;  ///< Dm^-1, Dm = [X1-X0, X2-X0, X3-X0]; F = Ds Dm^-1
  double rest_volume_m3 = 0.0;
};

/// Element data from rest positions X0..X3 (positive orientation assumed; checked by the model).
TetElement MakeTetElement(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                          const Eigen::Vector3d& x2, const Eigen::Vector3d& x3);

/// Block (a, b) of the linear stiffness, N/m:
/// K_ab = V (lambda g_a g_b^T + mu g_b g_a^T + mu (g_a . g_b) I).
inline Eigen::Matrix3d StiffnessBlock(const TetElement& e, double lambda, double mu, int a, int b) {
  const Eigen::Vector3d& ga = e.shape_gradients[a];
  const Eigen::Vector3d& gb = e.shape_gradients[b];
  Eigen::Matrix3d k = lambda * ga * gb.transpose() + mu * gb * ga.transpose();
  k.diagonal().array() += mu * ga.dot(gb);
  return e.rest_volume_m3 * k;
}

}  // namespace vesica::physics
