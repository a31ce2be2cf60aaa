#include "device/calibration/calibration_step.h"

#include "device/calibration/calibration_abort.h"
#include "device/calibration/servo_until.h"
#include "firmware_protocol/node/parameter_table.h"

namespace vesica::device::calibration {

void StepContext::RunUntil(const std::function<bool()>& done, double timeout_s, const std::string& what) {
  ServoUntil(link, servo, done, timeout_s, what);
}

void StepContext::EngageSelected() {
  for (int j = 0; j < 3; ++j)
    if (selected(j) && servo.mode(j) != JointServo::Mode::kTrack) servo.Engage(j, link.sample().position[j]);
}

void StepContext::RunFor(double seconds) {
  const double until = link.now_s() + seconds;
  RunUntil([&] { return link.now_s() >= until; }, seconds + 1.0, "timer");
}

void LoadNodeCalibration(StepContext& ctx) {
  CalibrationLink& l = ctx.link;
  for (int j = 0; j < 3; ++j) {
    const auto jj = static_cast<std::uint16_t>(j);
    JointCalibration& r = ctx.result.joint[j];
    r.direction = static_cast<std::int32_t>(l.ReadU32(fp::param::kEncoderDirection + jj)) < 0 ? -1 : 1;
    r.position_offset = l.ReadF32(fp::param::kPositionOffset + jj);
    r.current_offset_A = l.ReadF32(fp::param::kCurrentOffset + jj);
    r.lower_stop = l.ReadF32(fp::param::kJointMin + jj) - ctx.plan.range_margin[j];
    r.upper_stop = l.ReadF32(fp::param::kJointMax + jj) + ctx.plan.range_margin[j];
    r.index_position = l.ReadF32(fp::param::kIndexPosition + jj);
    r.coulomb = l.ReadF32(fp::param::kCoulombFriction + jj);
    r.viscous = l.ReadF32(fp::param::kViscousFriction + jj);
  }
  ctx.result.gravity_sin = l.ReadF32(fp::param::kGravitySin);
  ctx.result.gravity_cos = l.ReadF32(fp::param::kGravityCos);
}

}  // namespace vesica::device::calibration
