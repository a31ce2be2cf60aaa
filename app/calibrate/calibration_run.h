// One arm's measurement run: the core's steps (device/calibration/calibration_step.h) in order
// inside the node's calibration session, then, when asked and when every check passes, the
// results written and saved. Unlike ArmCalibrator it judges the numbers before anything is stored
// (a calibration out of tolerance is never saved) and can measure without saving (verify). Steps
// left out keep what the node has, and the steps that run start from it (LoadNodeCalibration).
// Any abort ends the session unsaved: the node zeroes the currents and reloads its stored
// calibration.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "app/calibrate/acceptance.h"
#include "app/calibrate/bus_observer.h"
#include "app/calibrate/calibration_steps.h"
#include "device/calibration/calibration_link.h"
#include "device/calibration/calibration_plan.h"
#include "device/calibration/calibration_result.h"

namespace vesica::app::calibrate {

struct RunRequest {
  device::calibration::CalibrationPlan plan;  ///< joints, limits, date and tool version
  std::vector<Step> steps = AllStepList();    ///< in the order of AllSteps()
  bool save = true;                           ///< false: measure only (verify)
  /// Judges the results before the save; a failing check leaves the stored calibration as it is.
  std::function<std::vector<Check>(const device::calibration::CalibrationResult&, const std::vector<Step>&)> judge;
};

struct RunOutcome {
  device::calibration::CalibrationResult result;
  std::vector<Step> steps;                  ///< that ran to their end
  std::vector<double> step_bus_time_s;      ///< each one's duration on the bus clock
  std::vector<Check> checks;                ///< the judge's
  bool out_of_tolerance = false;            ///< measured fully but a check failed: not saved
  std::vector<PositionSample> range_sweep;  ///< joint positions during the range step
  double bus_time_s = 0.0;                  ///< from connect to the end
};

RunOutcome RunCalibration(device::calibration::CalibrationLink& link, BusObserver& bus, const RunRequest& request);

}  // namespace vesica::app::calibrate
