// A static hold's torque, free of static friction: from a hold at an angle, a slowly rising
// current breaks the joint loose one way, then a falling one the other way; static friction adds
// to one break-away torque and takes from the other, so their mean is what holds the joint there
// (gravity on pitch, the reference load's spring in the torque-constant check).
#pragma once

#include "device/calibration/calibration_step.h"

namespace vesica::device::calibration {

struct HoldTorque {
  double at = 0.0;              ///< where the joint was held (mean of both holds), rad or m
  double breakaway_up = 0.0;    ///< N m or N, node torque units
  double breakaway_down = 0.0;  ///< N m or N
  double holding() const { return 0.5 * (breakaway_up + breakaway_down); }
};

/// Joint j (engaged in the servo) held at `position`, broken loose upward then downward with a
/// current ramp of plan.gravity_ramp_A_per_s. Throws CalibrationAbort kMeasurement naming `what`
/// when the joint will not hold still or holds against 90 % of the session's current.
HoldTorque MeasureHold(StepContext& ctx, int j, double position, const std::string& what);

}  // namespace vesica::device::calibration
