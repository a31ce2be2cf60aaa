// The JSON and text forms of what the commands read from a node (stable keys: scripts read them).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "app/calibrate/acceptance.h"
#include "app/calibrate/bus_observer.h"
#include "app/calibrate/stored_calibration.h"
#include "device/calibration/calibration_result.h"
#include "device/calibration/node_info.h"

namespace vesica::app::calibrate {

std::string VersionText(std::uint32_t v);  ///< "1.2.3"
std::string DateText(std::uint32_t s);     ///< "2026-11-27 05:20 UTC", "unknown"
std::string SerialText(std::uint32_t s);   ///< "0x5E51CA01"

nlohmann::json ToJson(const device::calibration::NodeInfo& info, const NodeHeartbeat* hb);
nlohmann::json ToJson(const CalibrationValues& v);
nlohmann::json ToJson(const std::vector<Check>& checks);
nlohmann::json ToJson(const device::calibration::CalibrationResult& r);

/// "state pre_operational, fault none" from the heartbeat, or "state unknown".
std::string StateText(const NodeHeartbeat* hb);
/// A table of the checks for a terminal.
std::string ChecksText(const std::vector<Check>& checks);
/// Before/after table of the stored values.
std::string ValuesText(const CalibrationValues& v);

}  // namespace vesica::app::calibrate
