#include "firmware_protocol/emulator/hand_model.h"

#include <algorithm>
#include <cmath>

namespace vesica::fp::emulator {

bool HandScript::Add(double t_s, const HandTarget& target) {
  if (!keys_.empty() && t_s < keys_.back().t_s) return false;
  keys_.push_back({t_s, target});
  return true;
}

bool HandScript::RepeatFrom(double t_s) {
  if (keys_.empty() || !(t_s >= keys_.front().t_s && t_s < keys_.back().t_s)) return false;
  repeat_from_s_ = t_s;
  return true;
}

HandTarget HandScript::At(double t_s) const {
  if (keys_.empty()) return HandTarget{};
  if (repeat_from_s_ >= 0.0 && t_s > keys_.back().t_s)
    t_s = repeat_from_s_ + std::fmod(t_s - repeat_from_s_, keys_.back().t_s - repeat_from_s_);
  if (t_s <= keys_.front().t_s) return keys_.front().target;
  if (t_s >= keys_.back().t_s) return keys_.back().target;
  // Binary search: recorded scripts have thousands of keyframes and the plant asks at 10 kHz.
  const auto after = std::upper_bound(keys_.begin(), keys_.end(), t_s,
                                      [](double t, const Keyframe& k) { return t < k.t_s; });
  const Keyframe& a = *(after - 1);
  const Keyframe& b = *after;
  const double s = b.t_s > a.t_s ? (t_s - a.t_s) / (b.t_s - a.t_s) : 1.0;
  HandTarget out = a.target;  // discrete fields hold until the next keyframe
  for (int k = 0; k < 3; ++k) out.p_T[k] = a.target.p_T[k] + s * (b.target.p_T[k] - a.target.p_T[k]);
  out.roll_rad = a.target.roll_rad + s * (b.target.roll_rad - a.target.roll_rad);
  out.jaw_rad = a.target.jaw_rad + s * (b.target.jaw_rad - a.target.jaw_rad);
  if (a.target.pedal_travel >= 0.0 && b.target.pedal_travel >= 0.0)
    out.pedal_travel = a.target.pedal_travel + s * (b.target.pedal_travel - a.target.pedal_travel);
  return out;
}

Vec3 HandForceOnInstrument(const HandParameters& hand, const HandTarget& target, const Vec3& p_T,
                           const Vec3& v_T) {
  if (!target.holding) return {0.0, 0.0, 0.0};
  Vec3 f{};
  for (int k = 0; k < 3; ++k)
    f[k] = hand.stiffness_N_per_m * (target.p_T[k] - p_T[k]) - hand.damping_N_s_per_m * v_T[k];
  return f;
}

}  // namespace vesica::fp::emulator
