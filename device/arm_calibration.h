#pragma once

#include <Eigen/Core>
#include <array>

#include "device/arm_actuation.h"
#include "device/spherical_arm_kinematics.h"

namespace vesica::device {

/// What the host does with an arm's calibration. The node applies encoder directions, position
/// offsets and current-sensor offsets itself (firmware_protocol/node/node.h, tick()): its joint
/// states are calibrated positions, so the host must not apply them again. The host adds what
/// only it can: feed-forward efforts that cancel the joints' friction and hold pitch against
/// gravity, so the hand feels the commanded tip force and not the arm.
/// Efforts are in the node's torque units (joint torque = current * its torque constant * gear
/// ratio), the units the calibration measured them in. Joint order yaw, pitch, insertion.
struct ArmCalibration {
  std::array<double, 3> coulomb{};  ///< N m (N for insertion), >= 0
  std::array<double, 3> viscous{};  ///< N m s/rad (N s/m), >= 0
  /// Pitch holding torque = gravity_sin * sin(pitch) + gravity_cos * cos(pitch), N m.
  double gravity_sin = 0.0;
  double gravity_cos = 0.0;
  /// The node's joint effort per amp (its torque constant * gear ratio), > 0: turns the efforts
  /// into the currents the host sends.
  std::array<double, 3> effort_per_amp{};
  /// Below this speed Coulomb compensation fades linearly to zero (a velocity estimate from
  /// encoder steps is noisy at rest, and a joint at rest is held by static friction anyway):
  /// rad/s, rad/s, m/s, > 0.
  std::array<double, 3> coulomb_fade_speed{0.05, 0.05, 0.005};
  /// Protocol 1.3: the reference-load check's real torque per node torque unit (the motor's torque
  /// constant over the node's torque_constant parameter), 1 where not measured (a layout-1 image,
  /// a node below 1.3), in [0.5, 2].
  std::array<double, 3> torque_constant_correction{1.0, 1.0, 1.0};

  /// Efforts (yaw, pitch, insertion) that cancel Coulomb and viscous friction at joint
  /// velocities qd (ArmJoints order: yaw, pitch, roll, insertion) and hold pitch at q.
  Eigen::Vector3d CompensationEffort(const ArmJoints& q, const Eigen::Vector4d& qd) const;
  /// The same as motor currents, A. No torque-constant correction: the efforts were measured in
  /// the node's torque units, which carry the same error.
  Eigen::Vector3d CompensationCurrent(const ArmJoints& q, const Eigen::Vector4d& qd) const;
  /// The actuation as this arm's motors really are: each torque constant times its correction, so
  /// that a rendered tip force takes the current that really makes it.
  ArmActuation Corrected(const ArmActuation& nominal) const;
};

}  // namespace vesica::device
