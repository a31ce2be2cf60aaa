#pragma once
// The calibration's inner loop: servo periods on the link until a condition holds, shared by the
// calibration steps and homing.

#include <functional>
#include <string>

#include "device/calibration/calibration_link.h"
#include "device/calibration/joint_servo.h"

namespace vesica::device::calibration {

/// Cycles `link` with the servo's currents until done(), or throws CalibrationAbort kMeasurement
/// naming `what` after timeout_s of bus time. Link faults and aborts throw from inside.
void ServoUntil(CalibrationLink& link, JointServo& servo, const std::function<bool()>& done, double timeout_s,
                const std::string& what);

}  // namespace vesica::device::calibration
