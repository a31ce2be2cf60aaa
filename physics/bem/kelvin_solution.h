#pragma once
// Kelvin fundamental solutions of 3D linear elastostatics (Brebbia & Dominguez), the kernels of
// the BEM equation c u(xi) + int T* u dGamma = int U* t dGamma (gallbladder paper eq. 1).
// r = x - xi points from the source (collocation point xi) to the field point x; n is the outward
// normal at x.

#include <Eigen/Core>
#include <numbers>

namespace vesica::physics {

/// U*_ij = [(3-4nu) delta_ij + r,i r,j] / [16 pi mu (1-nu) r]  (m/N per m^2 of traction)
inline Eigen::Matrix3d KelvinDisplacement(const Eigen::Vector3d& r, double shear_modulus_Pa,
                                          double poisson_ratio) {
  const double length = r.norm();
  const Eigen::Vector3d dr = r / length;
  const double scale =
      1.0 / (16.0 * std::numbers::pi * shear_modulus_Pa * (1.0 - poisson_ratio) * length);
  return scale * ((3.0 - 4.0 * poisson_ratio) * Eigen::Matrix3d::Identity() + dr * dr.transpose());
}

/// T*_ij = -[dr/dn ((1-2nu) delta_ij + 3 r,i r,j) - (1-2nu)(r,i n_j - r,j n_i)] / [8 pi (1-nu) r^2]
inline Eigen::Matrix3d KelvinTraction(const Eigen::Vector3d& r, const Eigen::Vector3d& normal,
                                      double poisson_ratio) {
  const double length = r.norm();
  const Eigen::Vector3d dr = r / length;
  const double drdn = dr.dot(normal);
  const double a = 1.0 - 2.0 * poisson_ratio;
  const double scale = -1.0 / (8.0 * std::numbers::pi * (1.0 - poisson_ratio) * length * length);
  const Eigen::Matrix3d cross = dr * normal.transpose() - normal * dr.transpose();
  return scale * (drdn * (a * Eigen::Matrix3d::Identity() + 3.0 * dr * dr.transpose()) - a * cross);
}

}  // namespace vesica::physics
