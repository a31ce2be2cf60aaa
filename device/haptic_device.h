#pragma once

#include <array>
#include <cstdint>
#include <string>

#include <Eigen/Core>

#include "device/device_status.h"

namespace vesica::device {

/// What a haptic device can do, in the spirit of CHAI3D's cHapticDeviceInfo. Wide enough for a
/// 4-DOF laparoscopic arm (3-DOF force) and a 6-DOF Omni-style stylus (3-DOF force).
struct DeviceCapabilities {
  std::string model_name;
  int joint_count = 0;            ///< joints reported in JointState, <= kMaxJoints
  int position_dof = 0;           ///< tracked translational DOF of the tip
  int rotation_dof = 0;           ///< tracked rotational DOF of the tip
  int force_dof = 0;              ///< actuated translational DOF (SetTipForce)
  int torque_dof = 0;             ///< actuated rotational DOF (SetTipWrench torque part)
  bool has_gripper = false;       ///< jaw / handle angle sensor
  int button_count = 0;           ///< bits used in ToolState::buttons (pedal included)
  double max_force_N = 0.0;       ///< largest tip force magnitude the device renders
  double max_stiffness_N_per_m = 0.0;  ///< stable virtual stiffness at the servo rate
  double workspace_radius_m = 0.0;
  double servo_rate_hz = 0.0;
};

inline constexpr int kMaxJoints = 8;

/// Joint-space state, fixed size so the servo loop allocates nothing.
struct JointState {
  int count = 0;
  std::array<double, kMaxJoints> position{};  ///< rad or m per joint
  std::array<double, kMaxJoints> velocity{};  ///< rad/s or m/s
  std::array<double, kMaxJoints> effort{};    ///< N m or N, as commanded after saturation
};

/// Tip state in the device base frame B (for an arm: the trocar frame).
struct ToolState {
  Eigen::Vector3d p_BTip_B = Eigen::Vector3d::Zero();     ///< m
  Eigen::Matrix3d R_BTip = Eigen::Matrix3d::Identity();
  Eigen::Vector3d v_BTip_B = Eigen::Vector3d::Zero();     ///< m/s
  Eigen::Vector3d w_BTip_B = Eigen::Vector3d::Zero();     ///< rad/s
  double gripper_angle_rad = 0.0;                          ///< 0 = jaw closed
  std::uint32_t buttons = 0;                               ///< bit 0: pedal
  std::int64_t timestamp_ns = 0;                           ///< device clock of the sample
};

/// The host-side face of a haptic device (CHAI3D's cGenericHapticDevice, reduced). Calls are
/// cheap and non-blocking except Open(); the servo loop that talks to hardware is behind it.
class HapticDevice {
 public:
  virtual ~HapticDevice() = default;

  virtual DeviceStatus Open() = 0;
  virtual void Close() = 0;
  virtual const DeviceCapabilities& Capabilities() const = 0;
  /// kOk while the device renders forces; otherwise why not (link lost, node fault, ...).
  virtual DeviceStatus Status() const = 0;

  virtual JointState GetJointState() const = 0;
  virtual ToolState GetToolState() const = 0;

  /// Force on the user's hand at the tip, base frame, N. Saturated to the device's limits with
  /// the direction kept. Rejects non-finite input with kInvalidArgument.
  virtual DeviceStatus SetTipForce(const Eigen::Vector3d& f_B) = 0;
  /// Force and torque; devices without torque_dof ignore the torque part.
  virtual DeviceStatus SetTipWrench(const Eigen::Vector3d& f_B, const Eigen::Vector3d& /*torque_B*/) {
    return SetTipForce(f_B);
  }
  /// Clears a latched node fault after the user has seen it; forces restart from zero.
  virtual DeviceStatus ResetFault() = 0;
};

}  // namespace vesica::device
