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
    // In the element frame A = R^T F = S + W (symmetric + skew); R is the polar factor when W = 0.
    // Turning R by omega (element frame) changes W by -[(tr S I - S) omega / 2]x to first order,
    // so Newton's step solves (tr S I - S) omega = 2 axial(W) = torque (Mueller et al.'s torque,
    // which they divide by tr A instead: a 2/3-length step, linear convergence at rate ~1/3).
    // Far from the solution (tr S I - S not positive definite) their step is kept: it always
    // turns toward F.
    const Eigen::Matrix3d a = r.transpose() * F;
    const Eigen::Vector3d torque(a(2, 1) - a(1, 2), a(0, 2) - a(2, 0), a(1, 0) - a(0, 1));
    const double trace = a(0, 0) + a(1, 1) + a(2, 2);
    // J = tr S I - S (symmetric): entries, adjugate, Sylvester's test, J^-1 torque = adj(J) torque / det J.
    const double j00 = trace - a(0, 0), j11 = trace - a(1, 1), j22 = trace - a(2, 2);
    const double j01 = -0.5 * (a(0, 1) + a(1, 0)), j02 = -0.5 * (a(0, 2) + a(2, 0)), j12 = -0.5 * (a(1, 2) + a(2, 1));
    const double c00 = j11 * j22 - j12 * j12, c01 = j02 * j12 - j01 * j22, c02 = j01 * j12 - j02 * j11;
    const double c11 = j00 * j22 - j02 * j02, c12 = j01 * j02 - j00 * j12, c22 = j00 * j11 - j01 * j01;
    const double det = j00 * c00 + j01 * c01 + j02 * c02;
    const bool newton = j00 > 1e-3 * std::abs(trace) && c22 > 0.0 && det > 0.0;
    Eigen::Vector3d omega;
    if (newton) {
      omega = Eigen::Vector3d(c00 * torque.x() + c01 * torque.y() + c02 * torque.z(),
                              c01 * torque.x() + c11 * torque.y() + c12 * torque.z(),
                              c02 * torque.x() + c12 * torque.y() + c22 * torque.z()) /
              det;
    } else {
      omega = torque / (std::abs(trace) + 1e-9);
    }
    const double angle_squared = omega.squaredNorm();
    if (angle_squared < 1e-24) break;
    // Turn about omega by 2 atan(|omega| / 2) (the Cayley map: no sin/cos; the same step to second
    // order, so Newton stays quadratic).
    const Eigen::Quaterniond turn(1.0, 0.5 * omega.x(), 0.5 * omega.y(), 0.5 * omega.z());
    q = q * turn;
    q.normalize();
    r = q.toRotationMatrix();
    // A Newton step this small leaves an error of its square: converged to ~1e-12.
    if (newton && angle_squared < 1e-12) break;
  }
  return r;
}

}  // namespace vesica::physics
