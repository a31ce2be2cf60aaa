// Current-sensor offsets: the node averages its current readings with the bridges off.
#include "device/calibration/calibration_step.h"
#include "firmware_protocol/node/parameter_table.h"

namespace vesica::device::calibration {

void MeasureCurrentOffsets(StepContext& ctx) {
  ctx.Progress("current offset", 0.0);
  // Every selected motor off: the joints rest on friction or a stop meanwhile.
  for (int j = 0; j < 3; ++j)
    if (ctx.selected(j)) ctx.servo.Off(j);
  const double dt = 1e-3;
  ctx.link.RunNodeProcedure(fp::CalibrationProcedure::CurrentOffset, ctx.plan.joints, 0.0, 2.0,
                            [&] { return ctx.servo.Update(ctx.link.sample(), dt); });
  for (int j = 0; j < 3; ++j)
    if (ctx.selected(j))
      ctx.result.joint[j].current_offset_A =
          ctx.link.ReadF32(static_cast<std::uint16_t>(fp::param::kCurrentOffset + j));
  ctx.Progress("current offset", 1.0);
}

}  // namespace vesica::device::calibration
