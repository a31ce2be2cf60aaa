#pragma once

#include <cstdint>

#include "device/calibration/calibration_link.h"
#include "device/calibration/calibration_result.h"

namespace vesica::device::calibration {

/// Writes what protocol 1.3 (image layout 2) stores, inside the session before its save: the
/// torque-constant correction of each joint in `joints` whose check ran (its ratio), the roll
/// sensor offset, jaw span and pedal travel whose guided steps ran. A node that negotiated less
/// than 1.3 has no place for them: nothing is written and result.not_stored says so.
void StoreLayout2Results(CalibrationLink& link, std::uint8_t joints, CalibrationResult& result);

}  // namespace vesica::device::calibration
