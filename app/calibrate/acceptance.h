// What a calibration's numbers must satisfy to be kept: each measured value with its window
// (design limits of the arm and the fit's quality), and for `verify` how far a re-measurement may
// lie from what is stored. The report shows every check with its tolerance and pass/fail.
#pragma once

#include <string>
#include <vector>

#include "app/calibrate/calibration_steps.h"
#include "app/calibrate/stored_calibration.h"
#include "device/calibration/calibration_result.h"

namespace vesica::app::calibrate {

struct Check {
  std::string name;  ///< "yaw.coulomb", stable (JSON key)
  std::string unit;  ///< "N m", "rad", ...
  double value = 0.0;
  double lo = 0.0, hi = 0.0;  ///< pass when lo <= value <= hi
  bool pass = false;
};

/// Checks of a fresh calibration of `joints` (bit j), for the steps that ran.
std::vector<Check> AcceptanceChecks(const device::calibration::CalibrationResult& r, unsigned joints,
                                    const std::vector<Step>& steps);
/// Re-measurement against the stored calibration: |measured - stored| within the repeatability.
std::vector<Check> VerifyChecks(const device::calibration::CalibrationResult& r, const CalibrationValues& stored,
                                unsigned joints, const std::vector<Step>& steps,
                                const std::array<double, 3>& range_margin);
bool AllPass(const std::vector<Check>& checks);

const char* JointName(int j);

}  // namespace vesica::app::calibrate
