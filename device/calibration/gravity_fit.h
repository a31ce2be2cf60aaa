#pragma once

#include <vector>

#include "device/calibration/calibration_result.h"

namespace vesica::device::calibration {

/// Pitch holding torque from static holds, least squares: hold(a) = sin * sin(a) + cos * cos(a).
struct GravityFit {
  double sin = 0.0;
  double cos = 0.0;
  double rms = 0.0;
  bool ok = false;  ///< false with fewer than two holds
};

GravityFit FitGravity(const std::vector<GravityHold>& holds);

}  // namespace vesica::device::calibration
