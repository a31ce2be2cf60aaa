#pragma once

#include <vector>

#include "firmware_protocol/emulator/arm_geometry.h"

namespace vesica::fp::emulator {

/// The user's hand as a spring-damper pulling the instrument toward a scripted target. It acts
/// at the tip-equivalent point: the handle impedance reflected through the trocar fulcrum, so the
/// force it measures compares directly with the tip force the host commands.
struct HandParameters {
  double stiffness_N_per_m = 300.0;        ///< grip stiffness, human range 100..1000
  double damping_N_s_per_m = 5.0;          ///< >= 0
  double mass_kg = 0.3;                    ///< hand + handle, reflected to the tip, >= 0
  double roll_stiffness_Nm_per_rad = 0.3;  ///< fingers turning the shaft
  double roll_damping_Nm_s_per_rad = 0.005;
};

/// Where the hand wants the instrument to be, and what the fingers and foot do.
struct HandTarget {
  Vec3 p_T{0.0, 0.0, 0.12};  ///< tip target in the trocar frame, m
  double roll_rad = 0.0;
  double jaw_rad = 0.0;       ///< handle opening, 0 closed
  bool pedal = false;
  double pedal_travel = -1.0; ///< 0 released .. 1 pressed to its stop; < 0: pedal gives 0 or 1
  bool holding = true;        ///< false: the hand lets go (no force)
};

/// Keyframed targets, linearly interpolated in time; pedal, holding follow the latest keyframe.
/// After the last keyframe the script holds it, or, after RepeatFrom(t), plays [t, last] again and
/// again (a lead-in before t plays once), so a scripted hand can move for as long as it runs.
class HandScript {
 public:
  struct Keyframe {
    double t_s;
    HandTarget target;
  };
  HandScript() = default;
  explicit HandScript(HandTarget constant) : keys_{{0.0, constant}} {}
  /// Keyframes must be added in increasing time; an earlier one is ignored (returns false).
  bool Add(double t_s, const HandTarget& target);
  HandTarget At(double t_s) const;
  /// Repeat the keyframes from t_s (>= the first keyframe's time, < the last's) to the last one
  /// forever; the script should end where it is at t_s or the hand jumps. False (and no repeat)
  /// when t_s is outside that range.
  bool RepeatFrom(double t_s);
  bool empty() const { return keys_.empty(); }
  std::size_t size() const { return keys_.size(); }
  /// Time of the last keyframe (0 for an empty script), s.
  double end_s() const { return keys_.empty() ? 0.0 : keys_.back().t_s; }

 private:
  std::vector<Keyframe> keys_;
  double repeat_from_s_ = -1.0;  ///< < 0: no repeat
};

/// Force the hand puts on the instrument at the tip (T frame, N) for tip position p and
/// velocity v: K (target - p) - B v, plus the hand's inertia (-m a) handled by the plant.
Vec3 HandForceOnInstrument(const HandParameters& hand, const HandTarget& target, const Vec3& p_T,
                           const Vec3& v_T);

}  // namespace vesica::fp::emulator
