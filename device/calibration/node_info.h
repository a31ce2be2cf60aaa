#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "device/calibration/calibration_link.h"
#include "firmware_protocol/codec/protocol_enums.h"
#include "firmware_protocol/node/parameter_store.h"

namespace vesica::device::calibration {

/// What a technician's `info` shows about one arm, read over the protocol: identity, versions,
/// state, faults, and the calibration slots (which one is booted, which is corrupt, and when and
/// by which tool the booted calibration was made).
struct NodeInfo {
  NodeIdentity identity;
  std::uint32_t firmware_version = 0;  ///< major << 16 | minor << 8 | patch
  fp::FaultCode latched_fault = fp::FaultCode::None;
  std::uint32_t fault_count = 0;
  std::vector<fp::FaultCode> fault_history;  ///< newest first, up to 8
  int active_slot = -1;                      ///< 0 A, 1 B, -1 none (defaults in use)
  std::array<fp::StorageResult, 2> slot_status{fp::StorageResult::BadMagic, fp::StorageResult::BadMagic};
  std::array<std::uint32_t, 2> slot_generation{};
  std::uint32_t calibration_date_s = 0;
  std::uint32_t calibration_tool_version = 0;
  /// Image layout of the booted slot: 2 (protocol 1.3), 1 (a 1.0 .. 1.2 tool's, or any slot of a
  /// node below 1.3), 0 when none is booted.
  std::uint16_t stored_layout = 0;

  /// The parameters the booted image lacks (a layout-1 image: layout 2's, at neutral defaults).
  std::vector<std::string> AbsentFields() const;
  /// The slot's state in words: "ok", "blank", "corrupt (bad CRC)", ...
  static std::string SlotText(fp::StorageResult r);
  /// A few lines for a person: versions, faults, slots, naming a corrupt slot.
  std::string Describe() const;
};

/// Reads it (Connect first: a node below protocol 1.1 has no slots and is refused there).
NodeInfo ReadNodeInfo(CalibrationLink& link);

}  // namespace vesica::device::calibration
