#pragma once
// The inertia matrix of a voxelised body (seed eq. 9) and the principal axes the seed reads from
// it (section 4.3): the rib plane and the spine's axis.
//
// Eq. 9 as printed has +xy off the diagonal; the inertia tensor has -xy (with +xy the matrix is not
// a tensor: its eigenvectors turn with the frame). We use the tensor, about the centroid. The seed
// takes "the two highest eigenvalues" as the plane that holds most matter and "the higher
// eigenvalue" of the spine as its axis: that is the reading of the second-moment matrix
// S = integral r r^T dv = (trace(I) / 2) Id - I, which has the same eigenvectors as I with the order
// reversed. principal_axes are ordered by the spread of matter, largest first.

#include <Eigen/Core>
#include <span>

namespace vesica::physics {

struct InertiaAxes {
  Eigen::Vector3d centroid_m = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia_m5 = Eigen::Matrix3d::Zero();          ///< eq. 9 (tensor sign), about the centroid, m^3 * m^2
  Eigen::Matrix3d principal_axes = Eigen::Matrix3d::Identity();  ///< columns, unit, largest spread first
  Eigen::Vector3d second_moments_m5 = Eigen::Vector3d::Zero();   ///< eigenvalues of S, descending
};

/// points: #P voxel centres (world, m); voxel_volume_m3: dv. Throws std::invalid_argument on an
/// empty set.
[[nodiscard]] InertiaAxes ComputeInertiaAxes(std::span<const Eigen::Vector3d> points, double voxel_volume_m3);

}  // namespace vesica::physics
