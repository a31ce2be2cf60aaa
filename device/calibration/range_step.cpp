// Range discovery and the joint's zero: slow, torque-limited moves onto both hard stops.
#include <cmath>
#include <string>

#include "device/calibration/calibration_abort.h"
#include "device/calibration/calibration_step.h"
#include "firmware_protocol/node/parameter_table.h"

namespace vesica::device::calibration {
namespace {

// One joint's way through the step: seek the lower stop, back off, seek the upper one.
struct StopSeeker {
  enum class Phase { kSeekLower, kLeaveLower, kSeekUpper, kDone };
  Phase phase = Phase::kSeekLower;
  int still_ms = 0;
  int push_ms = 0;
  double push_sum = 0.0;
  double lower = 0.0, upper = 0.0;
};

}  // namespace

void FindRangeAndZero(StepContext& ctx) {
  ctx.Progress("range", 0.0);
  JointServo& servo = ctx.servo;
  const ArmDesign& d = servo.design();
  std::array<StopSeeker, 3> seek;
  const double far = 4.0;  // beyond any stop: the reference keeps pulling until the stop holds it
  for (int j = 0; j < 3; ++j) {
    if (!ctx.selected(j)) {
      seek[j].phase = StopSeeker::Phase::kDone;
      continue;
    }
    servo.Engage(j, ctx.link.sample().position[j]);
    servo.SetTorqueLimit(j, ctx.plan.seek_torque[j]);
    servo.MoveTo(j, ctx.link.sample().position[j] - far, ctx.plan.seek_speed[j]);
  }
  auto all_done = [&] {
    bool done = true;
    for (int j = 0; j < 3; ++j) {
      StopSeeker& s = seek[j];
      if (s.phase == StopSeeker::Phase::kDone) continue;
      done = false;
      const double p = ctx.link.sample().position[j];
      const bool rotary = j < 2;
      // On a stop: the reference has run well past the joint and the joint stands still.
      const bool pushing = std::abs(servo.reference(j) - p) > (rotary ? 0.05 : 5e-3) &&
                           std::abs(servo.velocity(j)) < (rotary ? 0.01 : 1e-3);
      if (s.phase == StopSeeker::Phase::kSeekLower || s.phase == StopSeeker::Phase::kSeekUpper) {
        s.still_ms = pushing ? s.still_ms + 1 : 0;
        if (s.still_ms > 100) {  // then average the position over 50 ms of full push
          s.push_sum += p;
          if (++s.push_ms == 50) {
            const double stop = s.push_sum / s.push_ms;
            s.push_ms = 0;
            s.push_sum = 0.0;
            s.still_ms = 0;
            servo.Engage(j, p);
            if (s.phase == StopSeeker::Phase::kSeekLower) {
              s.lower = stop;
              servo.MoveTo(j, stop + (rotary ? 0.1 : 0.01), ctx.plan.move_speed[j]);
              s.phase = StopSeeker::Phase::kLeaveLower;
            } else {
              s.upper = stop;
              servo.MoveTo(j, 0.5 * (s.lower + s.upper), ctx.plan.move_speed[j]);
              s.phase = StopSeeker::Phase::kDone;
            }
          }
        }
      } else if (s.phase == StopSeeker::Phase::kLeaveLower && servo.arrived(j)) {
        servo.MoveTo(j, p + far, ctx.plan.seek_speed[j]);
        s.phase = StopSeeker::Phase::kSeekUpper;
      }
    }
    return done;
  };
  ctx.RunUntil(all_done, 60.0, "range: a hard stop was not found within 60 s");
  // Back to the middle, then the zero: the midpoint of the stops is the design centre.
  ctx.RunUntil(
      [&] {
        for (int j = 0; j < 3; ++j)
          if (ctx.selected(j) && !servo.arrived(j)) return false;
        return true;
      },
      30.0, "range: the joints did not return to the middle");
  for (int j = 0; j < 3; ++j) {
    if (!ctx.selected(j)) continue;
    const auto jj = static_cast<std::uint16_t>(j);
    const double mid = 0.5 * (seek[j].lower + seek[j].upper);
    const double shift = d.centre[j] - mid;
    const double offset = ctx.link.ReadF32(fp::param::kPositionOffset + jj) + shift;
    ctx.link.WriteF32(fp::param::kPositionOffset + jj, static_cast<float>(offset));
    JointCalibration& r = ctx.result.joint[j];
    r.position_offset = offset;
    r.lower_stop = seek[j].lower + shift;
    r.upper_stop = seek[j].upper + shift;
  }
  ctx.link.Cycle(servo.amps());  // a sample in the new frame
  for (int j = 0; j < 3; ++j)
    if (ctx.selected(j)) servo.Engage(j, ctx.link.sample().position[j]);
  ctx.RunFor(0.2);
  ctx.Progress("range", 1.0);
}

}  // namespace vesica::device::calibration
