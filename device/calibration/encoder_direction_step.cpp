// Encoder direction: a slowly rising current moves the joint; the reading must follow its sign.
#include <cmath>
#include <string>

#include "device/calibration/calibration_abort.h"
#include "device/calibration/calibration_step.h"
#include "firmware_protocol/node/parameter_table.h"

namespace vesica::device::calibration {
namespace {

// Ramps an open-loop current of `sign` until the joint has moved `distance`; the reading's
// change, or 0 when it never moved (against a stop, or blocked).
double RampUntilMoved(StepContext& ctx, int j, double sign, double max_amps, double distance) {
  // Only a joint at rest tells the current's direction: an unbalanced pitch may still be falling
  // onto a stop (motors off since power-up), and that motion says nothing.
  ctx.servo.Off(j);
  double last = ctx.link.sample().position[j];
  int still_ms = 0;
  ctx.RunUntil(
      [&] {
        const double p = ctx.link.sample().position[j];
        still_ms = std::abs(p - last) < 1.5e-4 ? still_ms + 1 : 0;
        if (still_ms == 0) last = p;
        return still_ms >= 200;
      },
      5.0, "encoder direction: joint " + std::to_string(j) + " did not come to rest with its motor off");
  const double start = ctx.link.sample().position[j];
  const double ramp_A_per_s = 0.5;
  double amps = 0.0;
  double moved = 0.0;
  int at_max_ms = 0;
  ctx.RunUntil(
      [&] {
        moved = ctx.link.sample().position[j] - start;
        if (std::abs(moved) >= distance) return true;
        if (amps >= max_amps && ++at_max_ms > 300) return true;  // blocked this way (a stop)
        amps = std::min(amps + ramp_A_per_s * 1e-3, max_amps);
        ctx.servo.Open(j, sign * amps);
        return false;
      },
      max_amps / ramp_A_per_s + 2.0, "encoder direction: ramp did not end");
  return moved;
}

}  // namespace

void FindEncoderDirections(StepContext& ctx) {
  ctx.Progress("encoder direction", 0.0);
  const ArmDesign& d = ctx.servo.design();
  int done = 0;
  // Pitch last: once found it is held against its imbalance while the others move.
  for (int j : {0, 2, 1}) {
    if (!ctx.selected(j)) continue;
    const auto jj = static_cast<std::uint16_t>(j);
    const int old_dir = static_cast<std::int32_t>(ctx.link.ReadU32(fp::param::kEncoderDirection + jj)) < 0 ? -1 : 1;
    const double max_amps = ctx.plan.seek_torque[j] / d.nm_per_A[j];
    const double distance = j == 2 ? 2e-3 : 0.01;
    double sign = 1.0;
    double moved = RampUntilMoved(ctx, j, +1.0, max_amps, distance);
    if (std::abs(moved) < distance) {  // resting on its upper stop: the other way
      sign = -1.0;
      moved = RampUntilMoved(ctx, j, -1.0, max_amps, distance);
    }
    ctx.servo.Off(j);
    if (std::abs(moved) < distance)
      throw CalibrationAbort(AbortReason::kMeasurement, "joint " + std::to_string(j) + " did not move under " +
                                                            std::to_string(max_amps) + " A either way (blocked?)");
    // Positive current moves every joint up; a reading that went down counts backwards.
    const int dir = (moved * sign > 0 ? 1 : -1) * old_dir;
    // Provisional zero: as if the arm had powered up parked where the board assumes.
    const double offset = d.park[j] * (1 - dir);
    ctx.link.WriteI32(fp::param::kEncoderDirection + jj, dir);
    ctx.link.WriteF32(fp::param::kPositionOffset + jj, static_cast<float>(offset));
    ctx.link.Cycle(ctx.servo.Update(ctx.link.sample(), 1e-3));  // a sample in the new frame
    ctx.servo.Engage(j, ctx.link.sample().position[j]);
    ctx.servo.SetTorqueLimit(j, ctx.plan.seek_torque[j]);
    ctx.result.joint[j].direction = dir;
    ctx.Progress("encoder direction", ++done / 3.0);
  }
  ctx.RunFor(0.2);  // settle what moved
}

}  // namespace vesica::device::calibration
