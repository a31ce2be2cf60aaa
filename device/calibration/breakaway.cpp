#include "device/calibration/breakaway.h"

#include <cmath>

#include "device/calibration/calibration_abort.h"

namespace vesica::device::calibration {
namespace {

// From a hold at `position`, ramp the current by `sign` until joint j moves that way; the torque
// then. The hold's current is first kept open loop for a moment: only a joint that stays put with
// it starts inside its static-friction band (a servo in stiction creeps and may sit at its edge).
// The ramp follows the bus clock, not the cycle count: a host that stalls ramps no faster.
double Breakaway(StepContext& ctx, int j, double position, double sign, double& held_at, const std::string& what) {
  JointServo& servo = ctx.servo;
  const ArmDesign& d = servo.design();
  const double limit = 0.9 * ctx.plan.session_max_current_A;
  // Detection: about 1.4 counts of a rotary joint, 1.5 of insertion.
  const double moved_by = j == 2 ? 3e-5 : 3e-4;
  const double rest_by = j == 2 ? 1.5e-5 : 1.5e-4;
  for (int attempt = 0; attempt < 5; ++attempt) {
    servo.Engage(j, ctx.link.sample().position[j]);
    servo.MoveTo(j, position, ctx.plan.move_speed[j]);
    ctx.RunUntil([&] { return servo.arrived(j); }, 20.0, what + ": did not reach the hold");
    servo.SetIntegral(j, false);  // comes to rest where the hold and static friction balance
    ctx.RunFor(0.3);
    servo.SetIntegral(j, true);
    const double hold_amps = servo.amps()[j];
    servo.Open(j, hold_amps);
    const double start = ctx.link.sample().position[j];
    held_at = start;
    ctx.RunFor(0.05);
    if (std::abs(ctx.link.sample().position[j] - start) > rest_by) continue;  // not at rest: again
    double moved = 0.0, amps = hold_amps;
    const double t0 = ctx.link.now_s();
    ctx.RunUntil(
        [&] {
          moved = ctx.link.sample().position[j] - start;
          if (std::abs(moved) > moved_by) return true;
          amps = hold_amps + sign * ctx.plan.gravity_ramp_A_per_s * (ctx.link.now_s() - t0);
          if (std::abs(amps) > limit)
            throw CalibrationAbort(AbortReason::kMeasurement, what + ": held against the current limit");
          servo.Open(j, amps);
          return false;
        },
        30.0, what + ": never broke loose");
    if (moved * sign > 0) {
      servo.Engage(j, ctx.link.sample().position[j]);
      return amps * d.nm_per_A[j];
    }
  }
  throw CalibrationAbort(AbortReason::kMeasurement, what + ": no steady hold at " + std::to_string(position));
}

}  // namespace

HoldTorque MeasureHold(StepContext& ctx, int j, double position, const std::string& what) {
  HoldTorque h;
  double up_at = 0.0, down_at = 0.0;
  h.breakaway_up = Breakaway(ctx, j, position, +1.0, up_at, what);
  h.breakaway_down = Breakaway(ctx, j, position, -1.0, down_at, what);
  h.at = 0.5 * (up_at + down_at);  // where it was held, not where it was sent
  return h;
}

}  // namespace vesica::device::calibration
