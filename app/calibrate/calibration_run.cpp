#include "app/calibrate/calibration_run.h"

#include "device/calibration/calibration_abort.h"
#include "device/calibration/calibration_step.h"
#include "device/calibration/joint_servo.h"
#include "device/calibration/layout2_results.h"
#include "firmware_protocol/node/parameter_table.h"

namespace vesica::app::calibrate {

namespace cal = device::calibration;
namespace param = fp::param;

namespace {

void RunStep(Step s, cal::StepContext& ctx) {
  switch (s) {
    case Step::kCurrentOffset:
      cal::MeasureCurrentOffsets(ctx);
      break;
    case Step::kEncoderDirection:
      cal::FindEncoderDirections(ctx);
      break;
    case Step::kRange:
      cal::FindRangeAndZero(ctx);
      break;
    case Step::kIndex:
      cal::FindReferenceIndex(ctx);
      break;
    case Step::kFriction:
      cal::IdentifyFriction(ctx);
      break;
    case Step::kGravity:
      cal::IdentifyGravity(ctx);
      break;
    case Step::kTorqueConstant:
      cal::CheckTorqueConstants(ctx);
      break;
    case Step::kRollOffset:
      cal::CalibrateRollOffset(ctx);
      break;
    case Step::kJawSpan:
      cal::CalibrateJawSpan(ctx);
      break;
    case Step::kPedalTravel:
      cal::CalibratePedalTravel(ctx);
      break;
  }
}

// The values the steps leave only in the result; what they write themselves (direction, offsets)
// is already on the node. Only what ran is written: the rest stays as stored.
void Commit(cal::CalibrationLink& link, const cal::CalibrationPlan& plan, RunOutcome& o, bool declare_home) {
  const auto ran = [&](Step s) {
    for (Step x : o.steps)
      if (x == s) return true;
    return false;
  };
  if (plan.progress) plan.progress("save", 0.0);
  for (int j = 0; j < 3; ++j) {
    if (!((plan.joints >> j) & 1u)) continue;
    const auto jj = static_cast<std::uint16_t>(j);
    const cal::JointCalibration& r = o.result.joint[j];
    if (ran(Step::kRange)) {
      link.WriteF32(param::kJointMin + jj, static_cast<float>(r.lower_stop + plan.range_margin[j]));
      link.WriteF32(param::kJointMax + jj, static_cast<float>(r.upper_stop - plan.range_margin[j]));
    }
    if (ran(Step::kIndex)) link.WriteF32(param::kIndexPosition + jj, static_cast<float>(r.index_position));
    if (ran(Step::kFriction)) {
      link.WriteF32(param::kCoulombFriction + jj, static_cast<float>(r.coulomb));
      link.WriteF32(param::kViscousFriction + jj, static_cast<float>(r.viscous));
    }
  }
  if (((plan.joints >> 1) & 1u) && ran(Step::kGravity)) {
    link.WriteF32(param::kGravitySin, static_cast<float>(o.result.gravity_sin));
    link.WriteF32(param::kGravityCos, static_cast<float>(o.result.gravity_cos));
  }
  cal::StoreLayout2Results(link, plan.joints, o.result);  // protocol 1.3: torque constant, hand sensors
  link.WriteU32(param::kCalibrationDate_s, plan.date_s);
  link.WriteU32(param::kCalibrationToolVersion, plan.tool_version);
  // Protocol 1.4: the range step measured this power-up's frame; saved, the node is homed with it.
  if (declare_home && ran(Step::kRange) && link.negotiated_minor() != 0xFF &&
      link.negotiated_minor() >= fp::kHomingMinor)
    link.DeclareHome();
  link.Save();
  if (plan.progress) plan.progress("save", 1.0);
}

}  // namespace

RunOutcome RunCalibration(cal::CalibrationLink& link, BusObserver& bus, const RunRequest& request) {
  RunOutcome o;
  const double t0 = link.now_s();
  std::string step = "connect";
  try {
    o.result.identity = link.Connect();
    link.ClearFault();
    // Protocol 1.4: a node not homed since power-up reads positions off by however far the arm
    // moved while off. The range step finds the frame again; steps without it need it homed.
    const bool not_homed = link.node_not_homed();
    bool range = false;
    for (Step s : request.steps) range = range || s == Step::kRange;
    if (not_homed && !range)
      throw cal::CalibrationAbort(cal::AbortReason::kRefused,
                                  "arm " + std::to_string(link.node_id()) +
                                      " is not homed since power-up (its positions are not known): run "
                                      "`vesica-calibrate home " +
                                      std::to_string(link.node_id()) + "` first, or a whole calibration");
    const bool declare_home = request.plan.joints == 0b111 || !not_homed;
    // The node's torque constant and ratio: the torques measured are in its units.
    cal::ArmDesign design;
    for (int j = 0; j < 3; ++j) {
      const auto jj = static_cast<std::uint16_t>(j);
      design.nm_per_A[j] = static_cast<double>(link.ReadF32(param::kTorqueConstant + jj)) *
                           static_cast<double>(link.ReadF32(param::kGearRatio + jj));
    }
    cal::JointServo servo(design);
    cal::StepContext ctx{link, servo, request.plan, o.result};
    step = "session";
    link.BeginSession(request.plan.joints, request.plan.session_max_current_A);
    cal::LoadNodeCalibration(ctx);  // what the steps left out keep, and where the others start
    for (Step s : request.steps) {
      step = InfoOf(s).name;
      if (s == Step::kRange) bus.StartRecording(link.node_id(), 0.01);
      const double start = link.now_s();
      RunStep(s, ctx);
      o.step_bus_time_s.push_back(link.now_s() - start);
      if (s == Step::kRange) {
        bus.StopRecording();
        o.range_sweep = bus.recorded();
      }
      o.steps.push_back(s);
    }
    if (request.judge) o.checks = request.judge(o.result, o.steps);
    o.out_of_tolerance = !AllPass(o.checks);
    if (!request.save || o.out_of_tolerance) {
      link.AbortSession();  // unsaved: the node reloads the stored calibration
      if (o.out_of_tolerance) {
        o.result.message =
            "a measured value is out of tolerance; nothing was saved, the stored calibration is in force";
        o.result.failed_step = "check";
      }
    } else {
      step = "save";
      Commit(link, request.plan, o, declare_home);
      o.result.saved = true;
    }
  } catch (const cal::CalibrationAbort& e) {
    bus.StopRecording();
    link.AbortSession();
    o.result.abort = e.reason();
    o.result.message = e.what();
    o.result.failed_step = step;
    o.result.saved = false;
  }
  o.bus_time_s = link.now_s() - t0;
  return o;
}

}  // namespace vesica::app::calibrate
