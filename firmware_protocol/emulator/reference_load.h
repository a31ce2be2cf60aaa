#pragma once

#include <array>

namespace vesica::fp::emulator {

/// The torque-constant check's test fixture: a certified spring the technician clamps between
/// the arm's base and its instrument, one per actuated joint (torsion springs on yaw and pitch, a
/// linear spring on the insertion carriage). Its stiffness is known, so the torque it takes to
/// hold a joint at two positions tells how much torque a motor current really gives.
struct ReferenceLoad {
  bool attached = false;
  std::array<double, 3> stiffness{};  ///< N m/rad (yaw, pitch), N/m (insertion), >= 0
  std::array<double, 3> neutral{};    ///< joint position where a spring pushes nothing: rad, rad, m

  /// Effort the spring puts on joint (motor) m at true joint position q: -k (q - neutral).
  double Effort(int m, double q) const { return attached ? -stiffness[m] * (q - neutral[m]) : 0.0; }
};

/// The standard fixture (docs/calibration.md, torque-constant check): 0.4 N m/rad on yaw and
/// pitch, 20 N/m on insertion, neutral at the joints' design centre (0 rad, 0 rad, 0.135 m). The
/// calibration plan's reference stiffness defaults to the same figures.
inline ReferenceLoad StandardReferenceLoad() { return ReferenceLoad{true, {0.4, 0.4, 20.0}, {0.0, 0.0, 0.135}}; }

}  // namespace vesica::fp::emulator
