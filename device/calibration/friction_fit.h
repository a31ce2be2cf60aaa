#pragma once

#include <vector>

#include "device/calibration/calibration_result.h"

namespace vesica::device::calibration {

/// Coulomb + viscous friction by least squares over sweep segments of both directions:
/// torque = coulomb * sign(v) + viscous * v + offset (the offset takes what does not depend on
/// the direction, e.g. pitch's mean gravity over the swept angles).
struct FrictionFit {
  double coulomb = 0.0;
  double viscous = 0.0;
  double offset = 0.0;
  double rms = 0.0;  ///< residual
  bool ok = false;   ///< false: too few segments or one direction missing
};

FrictionFit FitFriction(const std::vector<FrictionSegment>& segments);

}  // namespace vesica::device::calibration
