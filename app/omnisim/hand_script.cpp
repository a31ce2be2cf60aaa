#include "app/omnisim/hand_script.h"

#include <algorithm>
#include <cmath>

namespace vesica::app {

device::StylusRecording BuiltInBiopsyRecording(const BuiltInBiopsyMotion& motion) {
  // D points down and away from the user (-z), tilted from vertical by tilt_rad.
  const Eigen::Vector3d d(0.0, -std::cos(motion.tilt_rad), -std::sin(motion.tilt_rad));
  const Eigen::Vector3d start = motion.entry_m - motion.approach_m * d;
  const Eigen::Vector3d deepest = motion.entry_m + motion.insertion_m * d;
  auto smooth = [](double s) { return s * s * (3.0 - 2.0 * s); };  // zero speed at both ends
  device::StylusRecording rec;
  constexpr int kSamples = 651;  // 0 .. 6.5 s every 10 ms
  for (int i = 0; i < kSamples; ++i) {
    const double t = 0.01 * i;
    device::StylusSample s;
    s.time_s = t;
    s.state.d_B = d;
    if (t < 1.0) {
      s.state.p_BTip_B = start + smooth(t) * (motion.entry_m - start);
    } else if (t < 3.0) {
      s.state.p_BTip_B = motion.entry_m + smooth((t - 1.0) / 2.0) * (deepest - motion.entry_m);
    } else if (t < 4.0) {
      s.state.p_BTip_B = deepest;
      if (t >= 3.4 && t < 3.6) s.state.buttons = device::kStylusButton1;
    } else if (t < 6.0) {
      s.state.p_BTip_B = deepest + smooth((t - 4.0) / 2.0) * (start - deepest);
    } else {
      s.state.p_BTip_B = start;
    }
    rec.samples.push_back(s);
  }
  return rec;
}

HandScript::HandScript(device::StylusRecording recording)
    : replay_(std::move(recording)), period_s_(replay_.end_time_s() - replay_.start_time_s()) {}

device::StylusState HandScript::At(double t_s) const {
  const double local = period_s_ > 0 ? std::fmod(std::max(0.0, t_s), period_s_) : 0.0;
  return replay_.SampleAt(replay_.start_time_s() + local);
}

}  // namespace vesica::app
