#pragma once

#include <functional>
#include <string>

#include "device/calibration/calibration_link.h"
#include "device/calibration/calibration_plan.h"
#include "device/calibration/calibration_result.h"
#include "device/calibration/joint_servo.h"

namespace vesica::device::calibration {

/// What every calibration step works with: the link to the node (inside its calibration
/// session), the servo, the plan and the result it fills.
struct StepContext {
  CalibrationLink& link;
  JointServo& servo;
  const CalibrationPlan& plan;
  CalibrationResult& result;

  bool selected(int j) const { return (plan.joints >> j) & 1u; }
  /// Servo periods until done() or timeout_s of bus time (then CalibrationAbort kMeasurement
  /// naming `what`). Link faults and aborts throw from inside.
  void RunUntil(const std::function<bool()>& done, double timeout_s, const std::string& what);
  /// Servo periods for a while.
  void RunFor(double seconds);
  /// Every selected joint that is not yet tracking starts holding where it is (a step that
  /// follows a skipped one finds the joints off).
  void EngageSelected();
  void Progress(const std::string& step, double fraction) const {
    if (plan.progress) plan.progress(step, fraction);
  }
};

// The steps, in the order a calibration runs them (arm_calibrator.cpp). Each leaves the
// calibrated joints engaged in the servo at rest.

/// What the node runs on now, as a result: the starting point of a calibration that leaves
/// steps out (stops from joint_min/max and the plan's margin).
void LoadNodeCalibration(StepContext& ctx);
/// Current-sensor offsets, motors off (the node's procedure 2).
void MeasureCurrentOffsets(StepContext& ctx);
/// Encoder direction per joint: which way the reading goes under a small current.
void FindEncoderDirections(StepContext& ctx);
/// Both hard stops of every joint (slow, torque-limited); the joint's zero is their midpoint
/// (the stops are machined symmetric about the design centre), written as position_offset.
void FindRangeAndZero(StepContext& ctx);
/// The reference index edge (nearest the design centre) with the node's find-index procedure.
void FindReferenceIndex(StepContext& ctx);
/// Coulomb and viscous friction from constant-velocity sweeps, both directions.
void IdentifyFriction(StepContext& ctx);
/// Pitch's holding torque from static holds at several angles.
void IdentifyGravity(StepContext& ctx);
/// Each joint's real torque per node torque unit from static holds against the reference load
/// fixture (plan.reference_stiffness): the slope of the holding torque over position is the
/// spring's stiffness over the ratio. Pitch's gravity (as found or stored) is taken off first.
void CheckTorqueConstants(StepContext& ctx);
/// Guided hand motion (plan.hand_guide, protocol 1.2's raw readout; motors off): the roll
/// encoder's reading with the instrument at its reference, the jaw handle's ADC closed and open,
/// the pedal's released and pressed. A retry starts the step's prompts again; readings that fail
/// their check (span, travel) are prompted again up to plan.hand_attempts times, then refused.
void CalibrateRollOffset(StepContext& ctx);
void CalibrateJawSpan(StepContext& ctx);
void CalibratePedalTravel(StepContext& ctx);
/// The three above, in that order.
void CalibrateHandSensors(StepContext& ctx);

}  // namespace vesica::device::calibration
