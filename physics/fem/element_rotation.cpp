#include "physics/fem/element_rotation.h"

#include <Eigen/Geometry>
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

Eigen::Matrix3d RotationByQuaternionIteration(const Eigen::Matrix3d& F, Eigen::Vector4d& q_xyzw, int max_iterations) {
  Eigen::Map<Eigen::Quaterniond> q(q_xyzw.data());
  Eigen::Matrix3d r = q.toRotationMatrix();
  for (int it = 0; it < max_iterations; ++it) {
    // Rotate toward the columns of F: omega is the torque aligning R's axes with F's, scaled.
    const Eigen::Vector3d torque = r.col(0).cross(F.col(0)) + r.col(1).cross(F.col(1)) + r.col(2).cross(F.col(2));
    const double scale = std::abs(r.col(0).dot(F.col(0)) + r.col(1).dot(F.col(1)) + r.col(2).dot(F.col(2))) + 1e-9;
    const Eigen::Vector3d omega = torque / scale;
    const double angle_squared = omega.squaredNorm();
    if (angle_squared < 1e-24) break;
    // Turn about omega by 2 atan(|omega| / 2) (the Cayley map: no sin/cos): the same fixed point
    // (omega = 0) as Mueller's exp(omega), and the same step to second order near it.
    const Eigen::Quaterniond turn(1.0, 0.5 * omega.x(), 0.5 * omega.y(), 0.5 * omega.z());
    q = turn * q;
    q.normalize();
    r = q.toRotationMatrix();
  }
  return r;
}

}  // namespace vesica::physics
