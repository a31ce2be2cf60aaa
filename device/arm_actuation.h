#pragma once

#include <string_view>

#include <Eigen/Core>

#include "device/spherical_arm_kinematics.h"

namespace vesica::device {

/// One motor and its transmission to a joint, as the host knows it (datasheet or calibrated).
struct JointActuator {
  double torque_constant_Nm_per_A = 0.0;  ///< motor Kt, > 0
  /// Joint effort per unit motor torque, > 0: the gear ratio for yaw and pitch (dimensionless),
  /// 1 / capstan radius for the wire-driven insertion (1/m, so effort is in N).
  double transmission_ratio = 0.0;
  double max_current_A = 0.0;             ///< drive limit the host stays under, > 0

  double EffortPerAmp() const { return torque_constant_Nm_per_A * transmission_ratio; }
};

/// The three actuated joints of the spherical arm (roll is measured only).
struct ArmActuation {
  JointActuator yaw;
  JointActuator pitch;
  JointActuator insertion;
  double max_tip_force_N = 0.0;  ///< largest force magnitude rendered, > 0

  /// Nominal arm: brushed motors (30.2 mN m/A) on 14:1 gears for yaw and pitch, an ungeared
  /// BLDC (27.6 mN m/A) on a 10 mm capstan for insertion; the firmware node's parameter defaults
  /// and the emulator's plant carry the same figures.
  static ArmActuation Nominal();
  /// Empty string when every field is finite and positive, else the first offending field's name.
  std::string_view FirstInvalidField() const;
};

/// Which limit shaped the last command (the one that set the scale factor).
enum class ActuationLimit { kNone, kTipForce, kYawCurrent, kPitchCurrent, kInsertionCurrent };
std::string_view ToString(ActuationLimit limit);

/// Currents for a tip force, after saturation. The whole force is scaled by one factor so its
/// direction is kept (a clipped component would push the hand sideways).
struct MotorCurrentCommand {
  Eigen::Vector3d current_A = Eigen::Vector3d::Zero();      ///< yaw, pitch, insertion: tip force + feed-forward
  Eigen::Vector3d feedforward_A = Eigen::Vector3d::Zero();  ///< of current_A, what compensates the arm itself
  Eigen::Vector4d joint_effort = Eigen::Vector4d::Zero();   ///< the tip force's: yaw, pitch, roll (0), insertion
  Eigen::Vector3d f_rendered_T = Eigen::Vector3d::Zero();   ///< the force after scaling, N
  double scale = 1.0;                                       ///< in [0, 1]
  ActuationLimit active_limit = ActuationLimit::kNone;
};

/// Tip force (trocar frame, N) -> joint efforts by the Jacobian transpose -> motor currents
/// through transmission ratio and torque constant, saturated. A non-finite force gives zero.
/// feedforward_A (yaw, pitch, insertion; the arm's friction and gravity compensation,
/// ArmCalibration) is added after the scaling, clipped to each current limit: the tip force gets
/// the current left under each limit, so the sum stays within it.
MotorCurrentCommand TipForceToMotorCurrents(const ArmJoints& q, const Eigen::Vector3d& f_Tip_T,
                                            const ArmActuation& actuation,
                                            const Eigen::Vector3d& feedforward_A = Eigen::Vector3d::Zero());

}  // namespace vesica::device
