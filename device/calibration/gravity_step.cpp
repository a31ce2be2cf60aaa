// Pitch's holding torque: static holds at several angles. At each, a slowly rising current breaks
// the hold loose upward, then a falling one downward; the mean of the two is what holds the
// link against gravity (static friction adds to one and takes from the other).
#include <cmath>

#include "device/calibration/calibration_abort.h"
#include "device/calibration/calibration_step.h"
#include "device/calibration/gravity_fit.h"

namespace vesica::device::calibration {
namespace {

constexpr int kPitch = 1;

// From a hold at `angle`, ramp the current by `sign` until pitch moves that way; the torque then.
// The hold's current is first kept open loop for a moment: only a joint that stays put with it
// starts inside its static-friction band (a servo in stiction creeps and may sit at its edge).
double Breakaway(StepContext& ctx, double angle, double sign, double& held_at) {
  JointServo& servo = ctx.servo;
  const ArmDesign& d = servo.design();
  const double limit = 0.9 * ctx.plan.session_max_current_A;
  for (int attempt = 0; attempt < 5; ++attempt) {
    servo.Engage(kPitch, ctx.link.sample().position[kPitch]);
    servo.MoveTo(kPitch, angle, ctx.plan.move_speed[kPitch]);
    ctx.RunUntil([&] { return servo.arrived(kPitch); }, 20.0, "gravity: pitch did not reach its hold angle");
    servo.SetIntegral(kPitch, false);  // comes to rest where the hold and static friction balance
    ctx.RunFor(0.3);
    servo.SetIntegral(kPitch, true);
    double amps = servo.amps()[kPitch];
    servo.Open(kPitch, amps);
    const double start = ctx.link.sample().position[kPitch];
    held_at = start;
    ctx.RunFor(0.05);
    if (std::abs(ctx.link.sample().position[kPitch] - start) > 1.5e-4) continue;  // not at rest: again
    double moved = 0.0;
    ctx.RunUntil(
        [&] {
          moved = ctx.link.sample().position[kPitch] - start;
          if (std::abs(moved) > 3e-4) return true;  // about 1.4 counts
          amps += sign * ctx.plan.gravity_ramp_A_per_s * 1e-3;
          if (std::abs(amps) > limit)
            throw CalibrationAbort(AbortReason::kMeasurement, "gravity: pitch held against the current limit");
          servo.Open(kPitch, amps);
          return false;
        },
        30.0, "gravity: pitch never broke loose");
    if (moved * sign > 0) {
      servo.Engage(kPitch, ctx.link.sample().position[kPitch]);
      return amps * d.nm_per_A[kPitch];
    }
  }
  throw CalibrationAbort(AbortReason::kMeasurement,
                         "gravity: no steady hold of pitch at " + std::to_string(angle) + " rad");
}

}  // namespace

void IdentifyGravity(StepContext& ctx) {
  if (!ctx.selected(kPitch)) return;
  ctx.Progress("gravity", 0.0);
  ctx.EngageSelected();
  const JointCalibration& r = ctx.result.joint[kPitch];
  const int n = ctx.plan.gravity_angles < 2 ? 2 : ctx.plan.gravity_angles;
  const double lo = r.lower_stop + 0.15, hi = r.upper_stop - 0.15;
  ctx.result.gravity_holds.clear();
  for (int i = 0; i < n; ++i) {
    const double angle = lo + (hi - lo) * i / (n - 1);
    GravityHold h;
    double up_at = 0.0, down_at = 0.0;
    h.breakaway_up = Breakaway(ctx, angle, +1.0, up_at);
    h.breakaway_down = Breakaway(ctx, angle, -1.0, down_at);
    h.angle_rad = 0.5 * (up_at + down_at);  // where it was held, not where it was sent
    ctx.result.gravity_holds.push_back(h);
    ctx.Progress("gravity", static_cast<double>(i + 1) / n);
  }
  const GravityFit fit = FitGravity(ctx.result.gravity_holds);
  if (!fit.ok) throw CalibrationAbort(AbortReason::kMeasurement, "gravity: no fit");
  ctx.result.gravity_sin = fit.sin;
  ctx.result.gravity_cos = fit.cos;
  ctx.servo.MoveTo(kPitch, ctx.servo.design().centre[kPitch], ctx.plan.move_speed[kPitch]);
  ctx.RunUntil([&] { return ctx.servo.arrived(kPitch); }, 20.0, "gravity: pitch did not return to the centre");
}

}  // namespace vesica::device::calibration
