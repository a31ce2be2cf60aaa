// The reference index edge: from half an index spacing below the design centre, the node's
// find-index procedure creeps up to the first edge; the edge nearest the centre is found.
#include <cmath>

#include "device/calibration/calibration_step.h"
#include "firmware_protocol/node/parameter_table.h"

namespace vesica::device::calibration {

void FindReferenceIndex(StepContext& ctx) {
  ctx.Progress("index", 0.0);
  JointServo& servo = ctx.servo;
  ctx.EngageSelected();
  const ArmDesign& d = servo.design();
  int done = 0;
  for (int j = 0; j < 3; ++j) {
    if (!ctx.selected(j)) continue;
    const auto jj = static_cast<std::uint16_t>(j);
    servo.MoveTo(j, d.centre[j] - 0.5 * d.index_spacing[j], ctx.plan.move_speed[j]);
    ctx.RunUntil([&] { return servo.arrived(j); }, 20.0, "index: joint did not reach its start");
    ctx.RunFor(0.2);
    const double offset = ctx.link.ReadF32(fp::param::kPositionOffset + jj);
    // The node zeroes the joint at the edge: the offset's change is where the edge was.
    ctx.link.RunNodeProcedure(fp::CalibrationProcedure::FindIndex, static_cast<std::uint8_t>(1u << j),
                              ctx.plan.find_index_current_A[j], 10.0,
                              [&] { return servo.Update(ctx.link.sample(), 1e-3); });
    const double zeroed = ctx.link.ReadF32(fp::param::kPositionOffset + jj);
    ctx.result.joint[j].index_position = offset - zeroed;
    ctx.link.WriteF32(fp::param::kPositionOffset + jj, static_cast<float>(offset));  // the zero stays the stops'
    ctx.link.Cycle(servo.amps());
    servo.Engage(j, ctx.link.sample().position[j]);
    servo.MoveTo(j, d.centre[j], ctx.plan.move_speed[j]);
    ctx.Progress("index", ++done / 3.0);
  }
  ctx.RunUntil(
      [&] {
        for (int j = 0; j < 3; ++j)
          if (ctx.selected(j) && !servo.arrived(j)) return false;
        return true;
      },
      20.0, "index: joints did not return to the centre");
  ctx.Progress("index", 1.0);
}

}  // namespace vesica::device::calibration
