#include "device/calibration/joint_servo.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vesica::device::calibration {

JointServo::JointServo(const ArmDesign& design, double bandwidth_rad_s) : design_(design) {
  // Pole placement on the design inertia: stiff enough to track through friction, slow enough
  // for 0.1 mrad position steps at 1 kHz not to make noise of the velocity estimate.
  const double w = bandwidth_rad_s;
  for (int j = 0; j < 3; ++j) {
    kp_[j] = design.inertia[j] * w * w;
    kd_[j] = 2.0 * 0.8 * design.inertia[j] * w;
    ki_[j] = kp_[j] * w / 4.0;
    limit_[j] = 0.3 * design.nm_per_A[j];  // 0.3 A worth until the step sets its own
  }
}

void JointServo::Engage(int j, double position) {
  mode_[j] = Mode::kTrack;
  reference_[j] = target_[j] = position;
  speed_[j] = 0.0;
  integral_[j] = 0.0;
}

void JointServo::MoveTo(int j, double target, double speed) {
  target_[j] = target;
  speed_[j] = std::abs(speed);
}

void JointServo::Open(int j, double amps) {
  mode_[j] = Mode::kOpen;
  open_amps_[j] = amps;
}

std::array<double, 3> JointServo::Update(const LinkSample& s, double dt) {
  for (int j = 0; j < 3; ++j) {
    // Velocity from position differences, filtered at 30 Hz (positions come in 0.1 mrad steps).
    if (primed_[j] && dt > 0.0) {
      const double raw = (s.position[j] - last_position_[j]) / dt;
      const double a = 1.0 - std::exp(-2.0 * std::numbers::pi * 30.0 * dt);
      velocity_[j] += a * (raw - velocity_[j]);
    }
    last_position_[j] = s.position[j];
    primed_[j] = true;

    double tau = 0.0;
    if (mode_[j] == Mode::kTrack) {
      const double step = speed_[j] * dt;
      const double d = target_[j] - reference_[j];
      const double moving = std::abs(d) <= step ? 0.0 : std::copysign(speed_[j], d);
      reference_[j] = std::abs(d) <= step ? target_[j] : reference_[j] + std::copysign(step, d);
      const double e = reference_[j] - s.position[j];
      if (integral_on_[j]) integral_[j] += e * dt;
      // Anti-windup: the integral alone never asks for more than the limit.
      const double imax = ki_[j] > 0.0 ? limit_[j] / ki_[j] : 0.0;
      integral_[j] = std::clamp(integral_[j], -imax, imax);
      tau = kp_[j] * e + ki_[j] * integral_[j] + kd_[j] * (moving - velocity_[j]);
      tau = std::clamp(tau, -limit_[j], limit_[j]);
      amps_[j] = tau / design_.nm_per_A[j];
    } else if (mode_[j] == Mode::kOpen) {
      amps_[j] = open_amps_[j];
      tau = amps_[j] * design_.nm_per_A[j];
    } else {
      amps_[j] = 0.0;
    }
    torque_[j] = tau;
  }
  return amps_;
}

}  // namespace vesica::device::calibration
