#pragma once

#include <array>

#include "device/calibration/calibration_link.h"

namespace vesica::device::calibration {

/// What the calibration knows about the arm before it starts: design inertias (for the servo's
/// gains) and the node's torque constant and gear ratio (joint torque = current * kt * ratio).
struct ArmDesign {
  std::array<double, 3> inertia{3.2e-3, 2.2e-3, 0.144};                          ///< kg m^2, kg m^2, kg (with motors)
  std::array<double, 3> nm_per_A{0.0302 * 14.0, 0.0302 * 14.0, 0.0276 * 100.0};  ///< from the node
  std::array<double, 3> centre{0.0, 0.0, 0.135};  ///< stops are symmetric about this, rad / m
  /// Where the board assumes the arm powered up (its encoders count from there), rad / m.
  std::array<double, 3> park{0.0, 0.0, 0.135};
  std::array<double, 3> index_spacing{6.283185307179586 / 14.0, 6.283185307179586 / 14.0, 6.283185307179586 / 100.0};
};

/// Position servo of the three joints for the calibration's slow moves: per joint a PID on a
/// reference that ramps to its target at a set speed, output in joint torque clamped to a limit,
/// turned into motor current with the node's torque constant. A joint is off (zero current),
/// tracking, or driven open loop with a fixed current.
class JointServo {
 public:
  enum class Mode { kOff, kTrack, kOpen };

  explicit JointServo(const ArmDesign& design, double bandwidth_rad_s = 40.0);

  /// Starts tracking from the measured position (reference and integrator reset).
  void Engage(int j, double position);
  void Off(int j) { mode_[j] = Mode::kOff; }
  /// Ramp the reference toward target at speed (> 0), from where it is.
  void MoveTo(int j, double target, double speed);
  /// Open-loop current (A) until the next Engage / Off.
  void Open(int j, double amps);
  void SetTorqueLimit(int j, double limit) { limit_[j] = limit; }
  /// Without the integral a joint held in static friction comes to rest instead of creeping.
  void SetIntegral(int j, bool on) {
    integral_on_[j] = on;
    if (!on) integral_[j] = 0.0;
  }

  /// One period: currents for the latest sample.
  std::array<double, 3> Update(const LinkSample& s, double dt_s);

  Mode mode(int j) const { return mode_[j]; }
  bool arrived(int j) const { return reference_[j] == target_[j]; }
  double reference(int j) const { return reference_[j]; }
  double velocity(int j) const { return velocity_[j]; }  ///< filtered estimate
  double torque(int j) const { return torque_[j]; }      ///< last output, joint units
  double speed(int j) const { return speed_[j]; }
  const ArmDesign& design() const { return design_; }
  /// The current of the last output, A.
  const std::array<double, 3>& amps() const { return amps_; }

 private:
  ArmDesign design_;
  std::array<Mode, 3> mode_{Mode::kOff, Mode::kOff, Mode::kOff};
  std::array<double, 3> kp_{}, ki_{}, kd_{};
  std::array<double, 3> limit_{};
  std::array<double, 3> reference_{}, target_{}, speed_{};
  std::array<double, 3> integral_{};
  std::array<double, 3> velocity_{}, last_position_{};
  std::array<bool, 3> primed_{};
  std::array<bool, 3> integral_on_{true, true, true};
  std::array<double, 3> torque_{}, amps_{}, open_amps_{};
};

}  // namespace vesica::device::calibration
