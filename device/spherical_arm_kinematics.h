#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vesica::device {

/// Joint coordinates of one 4-DOF spherical remote-centre arm (gallbladder paper §2.5.4).
/// The remote centre (trocar pivot) is the origin of the trocar frame T, whose +z axis is the
/// nominal shaft direction into the patient. Order is the wire order of the joint-state frame.
struct ArmJoints {
  double yaw_rad = 0.0;      ///< about trocar y (left-right), (-pi/2, pi/2)
  double pitch_rad = 0.0;    ///< about the yawed x axis (up-down), (-pi/2, pi/2)
  double roll_rad = 0.0;     ///< about the shaft, measured only
  double insertion_m = 0.0;  ///< tip distance past the remote centre along the shaft, > 0 inside

  Eigen::Vector4d AsVector() const { return {yaw_rad, pitch_rad, roll_rad, insertion_m}; }
  static ArmJoints FromVector(const Eigen::Vector4d& q) { return {q[0], q[1], q[2], q[3]}; }
};

/// Pose of the instrument tip in the trocar frame: X_TTip.
struct TipPose {
  Eigen::Vector3d p_TTip_T = Eigen::Vector3d::Zero();       ///< m
  Eigen::Matrix3d R_TTip = Eigen::Matrix3d::Identity();    ///< shaft along the tip frame's +z
};

/// Forward kinematics: R_TTip = Ry(yaw) Rx(pitch) Rz(roll), p = insertion * (R_TTip e_z).
TipPose ForwardKinematics(const ArmJoints& q);

/// Geometric Jacobian, 6 by 4: rows 0-2 map joint rates to tip linear velocity in T (m/s),
/// rows 3-5 to tip angular velocity in T (rad/s). Columns follow ArmJoints' order.
Eigen::Matrix<double, 6, 4> TipJacobian(const ArmJoints& q);

/// Inverse kinematics from a full tip pose. Fails (returns false, q untouched) when the tip is
/// within min_insertion_m of the remote centre, where yaw and pitch are undefined, or when the
/// shaft points back out of the patient (|pitch| or |yaw| >= pi/2 is outside the arm's range).
bool InverseKinematics(const TipPose& pose, ArmJoints* q, double min_insertion_m = 1e-4);

/// Joint efforts that balance a force applied at the tip, tau = Jv^T f: N m for the rotary joints,
/// N for insertion. Roll gets zero: a tip force has no moment about the shaft.
Eigen::Vector4d JointEffortsFromTipForce(const ArmJoints& q, const Eigen::Vector3d& f_Tip_T);

/// The tip force the joint efforts produce, the least-squares inverse of JointEffortsFromTipForce
/// over the three actuated joints. Needs insertion > 0 (at the remote centre only insertion
/// force is available).
Eigen::Vector3d TipForceFromJointEfforts(const ArmJoints& q, const Eigen::Vector4d& tau);

}  // namespace vesica::device
