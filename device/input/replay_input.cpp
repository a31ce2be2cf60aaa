#include "device/input/replay_input.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace vesica::device {
namespace {

double Lerp(double a, double b, double alpha) { return a + alpha * (b - a); }

}  // namespace

ReplayInput::ReplayInput(InputRecording recording) : recording_(std::move(recording)) {
  if (recording_.frames.empty()) throw std::invalid_argument("ReplayInput: recording has no frames");
  for (std::size_t i = 0; i < recording_.frames.size(); ++i) {
    if (const auto problem = FrameProblem(recording_.frames[i], i == 0 ? nullptr : &recording_.frames[i - 1])) {
      throw std::invalid_argument("ReplayInput: frame " + std::to_string(i) + ": " + *problem);
    }
  }
}

double ReplayInput::duration_s() const { return end_time_s() - start_time_s(); }

InputFrame ReplayInput::Sample(double time_s) {
  if (std::isnan(time_s)) throw std::invalid_argument("ReplayInput::Sample: t is NaN");
  const std::vector<InputFrame>& frames = recording_.frames;
  InputFrame out;
  if (time_s <= frames.front().time_s) {
    out = frames.front();
    cursor_ = 0;
  } else if (time_s >= frames.back().time_s) {
    out = frames.back();
    cursor_ = frames.size() - 1;
  } else {
    // Find i with frames[i].time_s <= t < frames[i+1].time_s: step forward from the cursor
    // (playback moves forward a frame or so per step), binary search otherwise.
    std::size_t i = cursor_;
    if (!(frames[i].time_s <= time_s)) i = 0;
    for (int steps = 0; steps < 4 && frames[i + 1].time_s <= time_s; ++steps) ++i;
    if (frames[i + 1].time_s <= time_s) {
      const auto after = std::upper_bound(frames.begin() + static_cast<std::ptrdiff_t>(i), frames.end(), time_s,
                                          [](double t, const InputFrame& f) { return t < f.time_s; });
      i = static_cast<std::size_t>(after - frames.begin()) - 1;
    }
    cursor_ = i;
    const InputFrame& a = frames[i];
    const InputFrame& b = frames[i + 1];
    const double alpha = (time_s - a.time_s) / (b.time_s - a.time_s);
    for (int side = 0; side < 2; ++side) {
      const physics::InstrumentPose& pa = a.instruments[side].pose;
      const physics::InstrumentPose& pb = b.instruments[side].pose;
      physics::InstrumentPose& p = out.instruments[side].pose;
      p.yaw_rad = Lerp(pa.yaw_rad, pb.yaw_rad, alpha);
      p.pitch_rad = Lerp(pa.pitch_rad, pb.pitch_rad, alpha);
      p.roll_rad = Lerp(pa.roll_rad, pb.roll_rad, alpha);
      p.insertion_m = std::max(0.0, Lerp(pa.insertion_m, pb.insertion_m, alpha));  // rounding never below 0
      p.jaw_angle_rad = Lerp(pa.jaw_angle_rad, pb.jaw_angle_rad, alpha);
      out.instruments[side].pedal = a.instruments[side].pedal;
    }
    out.right_tool = a.right_tool;  // an exchange takes effect at its frame
  }
  out.time_s = time_s;
  return out;
}

}  // namespace vesica::device
