#include "device/calibration/arm_calibrator.h"

#include "device/calibration/calibration_abort.h"
#include "device/calibration/calibration_step.h"
#include "device/calibration/layout2_results.h"
#include "firmware_protocol/node/parameter_table.h"

namespace vesica::device::calibration {

ArmCalibrator::ArmCalibrator(CalibrationLink& link, const CalibrationPlan& plan, const ArmDesign& design)
    : link_(link), plan_(plan), design_(design) {}

CalibrationResult ArmCalibrator::Run() {
  CalibrationResult result;
  std::string step = "connect";
  try {
    result.identity = link_.Connect();
    link_.ClearFault();
    // Protocol 1.4: a node not homed since power-up reads positions off by however far the arm
    // moved while off. A whole calibration finds the frame again (range); single steps need it.
    const bool not_homed = link_.node_not_homed();
    if (not_homed && !(plan_.steps & kStepRange))
      throw CalibrationAbort(AbortReason::kRefused,
                             "node " + std::to_string(link_.node_id()) +
                                 " is not homed since power-up (its positions are not known): run `vesica-calibrate "
                                 "home " +
                                 std::to_string(link_.node_id()) + "` first, or a whole calibration");
    declare_home_ = (plan_.steps & kStepRange) && (plan_.joints == 0b111 || !not_homed);
    // The node's own torque constant and ratio: the torques measured are in its units.
    for (int j = 0; j < 3; ++j) {
      const auto jj = static_cast<std::uint16_t>(j);
      design_.nm_per_A[j] = static_cast<double>(link_.ReadF32(fp::param::kTorqueConstant + jj)) *
                            static_cast<double>(link_.ReadF32(fp::param::kGearRatio + jj));
    }
    JointServo servo(design_);
    StepContext ctx{link_, servo, plan_, result};
    step = "session";
    link_.BeginSession(plan_.joints, plan_.session_max_current_A);
    LoadNodeCalibration(ctx);
    const struct {
      std::uint8_t bit;
      const char* name;
      void (*run)(StepContext&);
    } steps[] = {{kStepCurrentOffset, "current offset", MeasureCurrentOffsets},
                 {kStepEncoderDirection, "encoder direction", FindEncoderDirections},
                 {kStepRange, "range", FindRangeAndZero},
                 {kStepIndex, "index", FindReferenceIndex},
                 {kStepFriction, "friction", IdentifyFriction},
                 {kStepGravity, "gravity", IdentifyGravity},
                 {kStepTorqueConstant, "torque constant", CheckTorqueConstants},
                 {kStepHandSensors, "hand sensors", CalibrateHandSensors}};
    for (const auto& s : steps) {
      if (!(plan_.steps & s.bit)) continue;
      step = s.name;
      s.run(ctx);
    }
    step = "save";
    Commit(result);
  } catch (const CalibrationAbort& e) {
    // Unsaved: the node reloads the stored calibration (it does so by itself on a fault or a
    // lost host; the abort frame covers a request and the tool's own errors).
    link_.AbortSession();
    result.abort = e.reason();
    result.message = e.what();
    result.failed_step = step;
    result.saved = false;
  }
  return result;
}

void ArmCalibrator::Commit(CalibrationResult& result) {
  if (plan_.progress) plan_.progress("save", 0.0);
  for (int j = 0; j < 3; ++j) {
    if (!((plan_.joints >> j) & 1u)) continue;
    const auto jj = static_cast<std::uint16_t>(j);
    const JointCalibration& r = result.joint[j];
    link_.WriteF32(fp::param::kJointMin + jj, static_cast<float>(r.lower_stop + plan_.range_margin[j]));
    link_.WriteF32(fp::param::kJointMax + jj, static_cast<float>(r.upper_stop - plan_.range_margin[j]));
    link_.WriteF32(fp::param::kIndexPosition + jj, static_cast<float>(r.index_position));
    link_.WriteF32(fp::param::kCoulombFriction + jj, static_cast<float>(r.coulomb));
    link_.WriteF32(fp::param::kViscousFriction + jj, static_cast<float>(r.viscous));
  }
  if ((plan_.joints >> 1) & 1u) {
    link_.WriteF32(fp::param::kGravitySin, static_cast<float>(result.gravity_sin));
    link_.WriteF32(fp::param::kGravityCos, static_cast<float>(result.gravity_cos));
  }
  StoreLayout2Results(link_, plan_.joints, result);
  // The range step measured this power-up's frame: the node is homed with what is saved.
  if (declare_home_ && link_.negotiated_minor() != 0xFF && link_.negotiated_minor() >= fp::kHomingMinor)
    link_.DeclareHome();
  link_.WriteU32(fp::param::kCalibrationDate_s, plan_.date_s);
  link_.WriteU32(fp::param::kCalibrationToolVersion, plan_.tool_version);
  link_.Save();
  result.saved = true;
  if (plan_.progress) plan_.progress("save", 1.0);
}

}  // namespace vesica::device::calibration
