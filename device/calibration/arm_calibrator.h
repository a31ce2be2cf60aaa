#pragma once

#include "device/calibration/calibration_link.h"
#include "device/calibration/calibration_plan.h"
#include "device/calibration/calibration_result.h"
#include "device/calibration/joint_servo.h"

namespace vesica::device::calibration {

/// A whole calibration of one arm over its link: connect (protocol 1.1 or newer), clear a latched
/// fault, open the node's calibration session, current offsets, encoder directions, range and
/// zero, reference index, friction, pitch gravity, then write everything and Save (the node puts
/// it in its older slot). Any CalibrationAbort on the way ends the session unsaved: the node
/// zeroes torque and reloads its stored calibration; the result says what happened.
class ArmCalibrator {
 public:
  ArmCalibrator(CalibrationLink& link, const CalibrationPlan& plan, const ArmDesign& design = {});

  CalibrationResult Run();

 private:
  void Commit(CalibrationResult& result);

  CalibrationLink& link_;
  CalibrationPlan plan_;
  ArmDesign design_;
  bool declare_home_ = false;  ///< the range step finds the frame of every joint not homed
};

}  // namespace vesica::device::calibration
