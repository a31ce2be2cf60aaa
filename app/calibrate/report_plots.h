// The report's plots as PNG files, drawn with Qt's QPainter on a QImage (no display needed: a
// QGuiApplication on the "offscreen" platform is made when the caller has none).
#pragma once

#include <string>
#include <vector>

#include "app/calibrate/bus_observer.h"
#include "device/calibration/calibration_result.h"

namespace vesica::app::calibrate {

/// Per calibrated joint: each sweep's mean velocity and torque, and the fitted
/// offset + Coulomb sign(v) + viscous v. False with a message when the file cannot be written.
bool PlotFrictionFit(const device::calibration::CalibrationResult& r, unsigned joints, const std::string& path,
                     std::string* error);
/// Per calibrated joint: its position through the range step (the node's frame at the time of
/// the sweep) and the two stops it came to rest on.
bool PlotRangeSweep(const std::vector<PositionSample>& sweep, unsigned joints, const std::string& path,
                    std::string* error);

}  // namespace vesica::app::calibrate
