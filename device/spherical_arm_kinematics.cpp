#include "device/spherical_arm_kinematics.h"

#include <algorithm>
#include <cmath>

namespace vesica::device {
namespace {

Eigen::Matrix3d ShaftRotation(double yaw, double pitch) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

}  // namespace

TipPose ForwardKinematics(const ArmJoints& q) {
  TipPose pose;
  pose.R_TTip = ShaftRotation(q.yaw_rad, q.pitch_rad) *
                Eigen::AngleAxisd(q.roll_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  pose.p_TTip_T = q.insertion_m * pose.R_TTip.col(2);
  return pose;
}

Eigen::Matrix<double, 6, 4> TipJacobian(const ArmJoints& q) {
  const double cy = std::cos(q.yaw_rad), sy = std::sin(q.yaw_rad);
  const double cp = std::cos(q.pitch_rad), sp = std::sin(q.pitch_rad);
  const double d = q.insertion_m;
  // Shaft axis z = Ry(yaw) Rx(pitch) e_z = (cp sy, -sp, cp cy).
  const Eigen::Vector3d axis(cp * sy, -sp, cp * cy);
  Eigen::Matrix<double, 6, 4> J = Eigen::Matrix<double, 6, 4>::Zero();
  J.block<3, 1>(0, 0) = d * Eigen::Vector3d(cp * cy, 0.0, -cp * sy);
  J.block<3, 1>(0, 1) = d * Eigen::Vector3d(-sp * sy, -cp, -sp * cy);
  J.block<3, 1>(0, 3) = axis;
  // Angular: yaw about T's y, pitch about the yawed x, roll about the shaft.
  J.block<3, 1>(3, 0) = Eigen::Vector3d::UnitY();
  J.block<3, 1>(3, 1) = Eigen::Vector3d(cy, 0.0, -sy);
  J.block<3, 1>(3, 2) = axis;
  return J;
}

bool InverseKinematics(const TipPose& pose, ArmJoints* q, double min_insertion_m) {
  const double d = pose.p_TTip_T.norm();
  if (!(d >= min_insertion_m) || !pose.p_TTip_T.allFinite()) return false;
  const Eigen::Vector3d axis = pose.p_TTip_T / d;
  if (axis.z() <= 0.0) return false;  // shaft pointing out of the patient
  ArmJoints out;
  out.insertion_m = d;
  out.pitch_rad = std::asin(std::clamp(-axis.y(), -1.0, 1.0));
  out.yaw_rad = std::atan2(axis.x(), axis.z());
  // Roll is what is left of R_TTip after undoing yaw and pitch: a rotation about z.
  const Eigen::Matrix3d R_roll = ShaftRotation(out.yaw_rad, out.pitch_rad).transpose() * pose.R_TTip;
  out.roll_rad = std::atan2(R_roll(1, 0), R_roll(0, 0));
  *q = out;
  return true;
}

Eigen::Vector4d JointEffortsFromTipForce(const ArmJoints& q, const Eigen::Vector3d& f_Tip_T) {
  return TipJacobian(q).topRows<3>().transpose() * f_Tip_T;
}

Eigen::Vector3d TipForceFromJointEfforts(const ArmJoints& q, const Eigen::Vector4d& tau) {
  // Columns yaw, pitch, insertion of Jv are orthogonal with norms d cp, d, 1: invert per column.
  const Eigen::Matrix<double, 6, 4> J = TipJacobian(q);
  Eigen::Vector3d f = Eigen::Vector3d::Zero();
  for (int j : {0, 1, 3}) {
    const Eigen::Vector3d c = J.block<3, 1>(0, j);
    const double n2 = c.squaredNorm();
    if (n2 > 1e-12) f += c * (tau[j] / n2);
  }
  return f;
}

}  // namespace vesica::device
