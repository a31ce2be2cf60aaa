#include "physics/fem/element_rotation.h"

#include <Eigen/LU>
#include <Eigen/SVD>

namespace vesica::physics {

Eigen::Matrix3d RotationFromDeformationGradient(const Eigen::Matrix3d& F) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d u = svd.matrixU();
  const Eigen::Matrix3d& v = svd.matrixV();
  // Singular values are sorted in decreasing order: column 2 belongs to the smallest one.
  if ((u * v.transpose()).determinant() < 0.0) u.col(2) = -u.col(2);
  return u * v.transpose();
}

}  // namespace vesica::physics
