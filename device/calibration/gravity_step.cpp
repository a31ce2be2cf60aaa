// Pitch's holding torque: static holds at several angles (breakaway.h), least squares over sin
// and cos of the angle.
#include <cmath>

#include "device/calibration/breakaway.h"
#include "device/calibration/calibration_abort.h"
#include "device/calibration/calibration_step.h"
#include "device/calibration/gravity_fit.h"

namespace vesica::device::calibration {
namespace {

constexpr int kPitch = 1;

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
    const HoldTorque hold = MeasureHold(ctx, kPitch, angle, "gravity: pitch");
    GravityHold h;
    h.angle_rad = hold.at;
    h.breakaway_up = hold.breakaway_up;
    h.breakaway_down = hold.breakaway_down;
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
