#include "app/armsim/hand_trajectory.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace vesica::app {

emu::HandScript HoldingHand(const emu::Vec3& p_T) {
  emu::HandTarget hold;
  hold.p_T = p_T;
  return emu::HandScript(hold);
}

emu::HandScript FigureEightHand(const emu::Vec3& centre_T, double amplitude_m, double period_s) {
  if (!(amplitude_m > 0.0) || !(period_s > 0.0) || !std::isfinite(amplitude_m) || !std::isfinite(period_s))
    throw std::invalid_argument("figure eight: amplitude_m and period_s must be finite and > 0, got " +
                                std::to_string(amplitude_m) + " and " + std::to_string(period_s));
  constexpr int kKeysPerLoop = 120;  // 3 degrees of phase: linear pieces the eye does not see
  emu::HandScript script;
  for (int k = 0; k <= kKeysPerLoop; ++k) {
    const double phase = 2.0 * std::numbers::pi * k / kKeysPerLoop;
    emu::HandTarget t;
    t.p_T = {centre_T[0] + amplitude_m * std::sin(phase), centre_T[1] + 0.5 * amplitude_m * std::sin(2.0 * phase),
             centre_T[2]};
    t.jaw_rad = 0.25 * (1.0 - std::cos(phase));
    script.Add(period_s * k / kKeysPerLoop, t);
  }
  script.RepeatFrom(0.0);
  return script;
}

emu::Vec3 TipInTrocarFrame(const physics::InstrumentPose& pose, double reference_elevation_rad,
                           double min_insertion_m) {
  // With the reference's azimuth taken as 0: reference d0 = (cos e0, 0, sin e0), T's axes
  // x = (0, -1, 0), y = z × x = (sin e0, 0, -cos e0), z = d0; the shaft's world direction is
  // (cos e cos yaw, cos e sin yaw, sin e) with e = e0 + pitch (physics::ShaftDirection).
  const double e0 = reference_elevation_rad;
  const double e = e0 + pose.pitch_rad;
  const emu::Vec3 d_W{std::cos(e) * std::cos(pose.yaw_rad), std::cos(e) * std::sin(pose.yaw_rad), std::sin(e)};
  const emu::Vec3 d_T{-d_W[1], std::sin(e0) * d_W[0] - std::cos(e0) * d_W[2],
                      std::cos(e0) * d_W[0] + std::sin(e0) * d_W[2]};
  const double insertion = std::max(pose.insertion_m, min_insertion_m);
  return {insertion * d_T[0], insertion * d_T[1], insertion * d_T[2]};
}

emu::HandScript RecordedHand(const device::InputRecording& recording, int instrument, double reference_elevation_rad,
                             const emu::Vec3& start_T, double lead_in_s) {
  if (recording.frames.empty()) throw std::invalid_argument("recorded hand: the recording has no frames");
  if (instrument != device::kLeft && instrument != device::kRight)
    throw std::invalid_argument("recorded hand: instrument must be 0 (left) or 1 (right), got " +
                                std::to_string(instrument));
  if (!(std::abs(reference_elevation_rad) < std::numbers::pi / 2))
    throw std::invalid_argument("recorded hand: the reference elevation must be in (-90, 90) degrees, got " +
                                std::to_string(reference_elevation_rad * 180.0 / std::numbers::pi));
  if (!(lead_in_s > 0.0)) throw std::invalid_argument("recorded hand: lead_in_s must be > 0");
  auto target_of = [&](const device::InputFrame& f) {
    const device::InstrumentInput& in = f.instruments[static_cast<std::size_t>(instrument)];
    emu::HandTarget t;
    t.p_T = TipInTrocarFrame(in.pose, reference_elevation_rad);
    t.roll_rad = in.pose.roll_rad;
    t.jaw_rad = in.pose.jaw_angle_rad;
    t.pedal = in.pedal;
    return t;
  };
  emu::HandScript script;
  emu::HandTarget start;
  start.p_T = start_T;
  script.Add(0.0, start);
  const double t0 = recording.frames.front().time_s;
  for (const device::InputFrame& f : recording.frames) script.Add(lead_in_s + (f.time_s - t0), target_of(f));
  emu::HandTarget last = target_of(recording.frames.back());
  last.pedal = false;  // the foot leaves the pedal when the recording ends
  script.Add(script.end_s() + 1e-3, last);
  emu::HandTarget back = target_of(recording.frames.front());
  back.pedal = false;  // no cautery while the hand returns
  script.Add(script.end_s() + lead_in_s, back);
  script.RepeatFrom(lead_in_s);
  return script;
}

}  // namespace vesica::app
