// Torque-constant check: the reference load fixture (a certified spring per joint, stiffness k)
// is clamped on. Holding a joint at position x takes a torque k (x - neutral) plus gravity's on
// pitch; the node turns current into torque with its torque_constant parameter, so the holding
// torque in its units rises with slope k / ratio, where ratio is the real torque constant over the
// parameter. Static holds (breakaway up and down, static friction cancelled) at several positions
// and a straight line through them give the slope; neutral and offsets drop out with the line's
// intercept.
#include <cmath>
#include <string>

#include "device/calibration/breakaway.h"
#include "device/calibration/calibration_abort.h"
#include "device/calibration/calibration_step.h"

namespace vesica::device::calibration {
namespace {

const char* const kJointNames[3] = {"yaw", "pitch", "insertion"};

// Least-squares slope of torque over position.
double Slope(const std::vector<LoadHold>& holds) {
  double mx = 0.0, my = 0.0;
  for (const LoadHold& h : holds) {
    mx += h.position;
    my += h.torque;
  }
  mx /= static_cast<double>(holds.size());
  my /= static_cast<double>(holds.size());
  double sxy = 0.0, sxx = 0.0;
  for (const LoadHold& h : holds) {
    sxy += (h.position - mx) * (h.torque - my);
    sxx += (h.position - mx) * (h.position - mx);
  }
  return sxx > 0.0 ? sxy / sxx : 0.0;
}

}  // namespace

void CheckTorqueConstants(StepContext& ctx) {
  ctx.Progress("torque constant", 0.0);
  ctx.EngageSelected();
  const int n = ctx.plan.torque_constant_holds < 2 ? 2 : ctx.plan.torque_constant_holds;
  int selected = 0, done = 0;
  for (int j = 0; j < 3; ++j) selected += ctx.selected(j) ? 1 : 0;
  for (int j = 0; j < 3; ++j) {
    if (!ctx.selected(j)) continue;
    const std::string what = std::string("torque constant: ") + kJointNames[j];
    if (!(ctx.plan.reference_stiffness[j] > 0.0))
      throw CalibrationAbort(AbortReason::kMeasurement, what + ": the reference load's stiffness must be > 0");
    JointCalibration& r = ctx.result.joint[j];
    r.load_holds.clear();
    const double centre = ctx.servo.design().centre[j];
    const double span = ctx.plan.torque_constant_span[j];
    for (int i = 0; i < n; ++i) {
      const double position = centre - span + 2.0 * span * i / (n - 1);
      const HoldTorque h = MeasureHold(ctx, j, position, what);
      double torque = h.holding();
      if (j == 1) torque -= ctx.result.gravity_sin * std::sin(h.at) + ctx.result.gravity_cos * std::cos(h.at);
      r.load_holds.push_back({h.at, torque});
      ctx.Progress("torque constant", (done + static_cast<double>(i + 1) / n) / selected);
    }
    const double slope = Slope(r.load_holds);
    // Below a tenth of the fixture's stiffness there is no spring to speak of.
    if (!(slope > 0.1 * ctx.plan.reference_stiffness[j]))
      throw CalibrationAbort(AbortReason::kMeasurement,
                             what +
                                 ": the holding torque does not rise with the position (is the reference load "
                                 "fixture clamped on?)");
    r.torque_constant_ratio = ctx.plan.reference_stiffness[j] / slope;
    ctx.servo.MoveTo(j, centre, ctx.plan.move_speed[j]);
    ctx.RunUntil([&] { return ctx.servo.arrived(j); }, 20.0, what + ": did not return to the centre");
    ++done;
  }
  ctx.Progress("torque constant", 1.0);
}

}  // namespace vesica::device::calibration
