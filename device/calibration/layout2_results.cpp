// Protocol 1.3's stored results (image layout 2), written before the session's save.
#include "device/calibration/layout2_results.h"

#include "firmware_protocol/node/parameter_table.h"

namespace vesica::device::calibration {

void StoreLayout2Results(CalibrationLink& link, std::uint8_t joints, CalibrationResult& result) {
  const HandSensorCalibration& h = result.hand;
  bool torque_constant = false;
  for (int j = 0; j < 3; ++j) torque_constant |= ((joints >> j) & 1u) && result.joint[j].torque_constant_ratio > 0.0;
  if (!torque_constant && !h.roll_measured && !h.jaw_measured && !h.pedal_measured) return;
  // A node below protocol 1.3 has nowhere to keep these: measured and reported, not stored.
  if (link.negotiated_minor() < fp::kLayout2Minor) {
    result.not_stored = "node " + std::to_string(link.node_id()) + " speaks protocol 1." +
                        std::to_string(link.negotiated_minor()) +
                        ": the torque-constant correction and the hand sensors' calibration are measured and "
                        "reported but not stored (they need 1.3; update the arm's firmware)";
    return;
  }
  for (int j = 0; j < 3; ++j) {
    const double ratio = result.joint[j].torque_constant_ratio;
    if (!((joints >> j) & 1u) || !(ratio > 0.0)) continue;
    link.WriteF32(static_cast<std::uint16_t>(fp::param::kTorqueConstantCorrection + j), static_cast<float>(ratio));
  }
  if (h.roll_measured) link.WriteF32(fp::param::kRollSensorOffset, static_cast<float>(h.roll_offset_rad));
  if (h.jaw_measured) {
    link.WriteU32(fp::param::kJawClosedCounts, static_cast<std::uint32_t>(h.jaw_closed_raw));
    link.WriteU32(fp::param::kJawOpenCounts, static_cast<std::uint32_t>(h.jaw_open_raw));
  }
  if (h.pedal_measured) {
    link.WriteU32(fp::param::kPedalReleasedCounts, static_cast<std::uint32_t>(h.pedal_up_raw));
    link.WriteU32(fp::param::kPedalPressedCounts, static_cast<std::uint32_t>(h.pedal_down_raw));
  }
}

}  // namespace vesica::device::calibration
