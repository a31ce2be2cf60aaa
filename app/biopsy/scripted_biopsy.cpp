#include "app/biopsy/scripted_biopsy.h"

#include <algorithm>
#include <cmath>

namespace vesica::app::biopsy {
namespace {

// 0 before a, 1 after b, a smoothstep between (the hand starts and stops without a jerk).
double Ease(double t, double a, double b) {
  const double s = std::clamp((t - a) / (b - a), 0.0, 1.0);
  return s * s * (3.0 - 2.0 * s);
}

}  // namespace

device::StylusRecording ScriptBiopsy(const StylusPlacement& placement, const ScriptedBiopsyPlan& plan) {
  device::StylusRecording recording;
  const Eigen::Vector3d direction = plan.direction_W.normalized();
  const long samples = std::lround(plan.withdraw_until_s / plan.sample_period_s);
  for (long i = 0; i <= samples; ++i) {
    const double t = static_cast<double>(i) * plan.sample_period_s;
    const double in =
        Ease(t, plan.hold_before_s, plan.insert_until_s) - Ease(t, plan.withdraw_from_s, plan.withdraw_until_s);
    physics::NeedlePose pose;
    pose.tip_m = plan.entry_above_skin_W + in * (plan.target_W - plan.entry_above_skin_W);
    pose.direction = direction;
    device::StylusSample sample;
    sample.time_s = t;
    sample.state = StylusForNeedle(placement, pose);
    // Pressed from the moment the target is reached (the sample is taken on the press).
    const bool pressed = t >= plan.insert_until_s - 1e-9 && t < plan.insert_until_s + plan.button_down_s - 1e-9;
    sample.state.buttons = pressed ? device::kStylusButton1 : 0u;
    recording.samples.push_back(sample);
  }
  return recording;
}

}  // namespace vesica::app::biopsy
