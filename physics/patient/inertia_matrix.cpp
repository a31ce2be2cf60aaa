#include "physics/patient/inertia_matrix.h"

#include <Eigen/Eigenvalues>
#include <stdexcept>

namespace vesica::physics {

InertiaAxes ComputeInertiaAxes(std::span<const Eigen::Vector3d> points, double voxel_volume_m3) {
  if (points.empty()) throw std::invalid_argument("inertia matrix of an empty set of voxels");
  InertiaAxes axes;
  for (const Eigen::Vector3d& p : points) axes.centroid_m += p;
  axes.centroid_m /= static_cast<double>(points.size());
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();  // integral r r^T dv about the centroid
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d r = p - axes.centroid_m;
    second.noalias() += r * r.transpose();
  }
  second *= voxel_volume_m3;
  // Eq. 9: diagonal integral of y^2 + z^2 etc., products of inertia off the diagonal.
  axes.inertia_m5 = second.trace() * Eigen::Matrix3d::Identity() - second;
  const Eigen::Matrix3d s = 0.5 * axes.inertia_m5.trace() * Eigen::Matrix3d::Identity() - axes.inertia_m5;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(s);
  for (int c = 0; c < 3; ++c) {  // Eigen sorts ascending; we want descending
    axes.principal_axes.col(c) = solver.eigenvectors().col(2 - c);
    axes.second_moments_m5(c) = solver.eigenvalues()(2 - c);
  }
  if (axes.principal_axes.determinant() < 0.0) axes.principal_axes.col(2) *= -1.0;
  return axes;
}

}  // namespace vesica::physics
