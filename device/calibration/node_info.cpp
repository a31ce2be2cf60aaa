#include "device/calibration/node_info.h"

#include <cstdio>
#include <ctime>

#include "firmware_protocol/node/parameter_table.h"

namespace vesica::device::calibration {
namespace {

std::string Version(std::uint32_t v) {
  return std::to_string(v >> 16) + "." + std::to_string((v >> 8) & 0xFF) + "." + std::to_string(v & 0xFF);
}

std::string Date(std::uint32_t s) {
  if (s == 0) return "unknown date";
  const std::time_t t = static_cast<std::time_t>(s);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char b[32];
  std::strftime(b, sizeof b, "%Y-%m-%d %H:%M UTC", &tm);
  return b;
}

}  // namespace

std::string NodeInfo::SlotText(fp::StorageResult r) {
  switch (r) {
    case fp::StorageResult::Ok:
      return "ok";
    case fp::StorageResult::BadMagic:
      return "blank";
    case fp::StorageResult::BadVersion:
      return "unreadable (newer layout)";
    case fp::StorageResult::BadSize:
      return "unreadable (other parameter set)";
    case fp::StorageResult::BadCrc:
      return "corrupt (bad CRC)";
  }
  return "?";
}

std::vector<std::string> NodeInfo::AbsentFields() const {
  std::vector<std::string> absent;
  if (stored_layout != 1) return absent;
  for (std::size_t i = 0; i < fp::kParameterCount; ++i)
    if (fp::parameter_layout(i) > 1 && fp::kParameterSpecs[i].persistent) absent.push_back(fp::kParameterSpecs[i].name);
  return absent;
}

std::string NodeInfo::Describe() const {
  std::string s = "node " + std::to_string(identity.node) + ", serial " + std::to_string(identity.serial) +
                  ", firmware " + Version(firmware_version) + ", protocol " + std::to_string(identity.protocol_major) +
                  "." + std::to_string(identity.max_minor) + "\n";
  s += "fault: " + std::string(latched_fault == fp::FaultCode::None ? "none" : fp::to_string(latched_fault)) + " (" +
       std::to_string(fault_count) + " recorded";
  if (!fault_history.empty()) {
    s += ", last:";
    for (fp::FaultCode f : fault_history) s += std::string(" ") + fp::to_string(f);
  }
  s += ")\n";
  if (active_slot < 0) {
    s += "calibration: none in force (defaults)\n";
  } else {
    s += std::string("calibration: slot ") + (active_slot == 0 ? "A" : "B") + ", generation " +
         std::to_string(slot_generation[static_cast<std::size_t>(active_slot)]) + ", " + Date(calibration_date_s) +
         ", tool " + Version(calibration_tool_version) + ", image layout " + std::to_string(stored_layout) + "\n";
    const std::vector<std::string> absent = AbsentFields();
    if (!absent.empty()) {
      s += identity.max_minor < fp::kLayout2Minor
               ? "  this node (protocol 1." + std::to_string(identity.max_minor) + ") keeps layout 1 only; it has no:"
               : std::string("  layout 1 (a 1.0 .. 1.2 tool's) lacks, neutral:");
      for (const std::string& name : absent) s += " " + name;
      s += "\n";
    }
  }
  for (int k = 0; k < 2; ++k) {
    s += std::string("slot ") + (k == 0 ? "A" : "B") + ": " + SlotText(slot_status[k]);
    if (slot_status[k] == fp::StorageResult::Ok) s += ", generation " + std::to_string(slot_generation[k]);
    if (k == active_slot) s += " (in use)";
    s += "\n";
  }
  return s;
}

NodeInfo ReadNodeInfo(CalibrationLink& link) {
  NodeInfo info;
  info.identity = link.Connect();
  info.firmware_version = link.ReadU32(fp::param::kFirmwareVersion);
  info.fault_count = link.ReadU32(fp::param::kFaultHistoryCount);
  const std::uint32_t depth =
      info.fault_count < fp::param::kFaultHistoryDepth ? info.fault_count : fp::param::kFaultHistoryDepth;
  for (std::uint32_t k = 0; k < depth; ++k) {
    const std::uint32_t code = link.ReadU32(static_cast<std::uint16_t>(fp::param::kFaultHistory + k)) & 0xFFu;
    if (code < fp::kFaultCodeCount) info.fault_history.push_back(static_cast<fp::FaultCode>(code));
  }
  link.AwaitHeartbeat();
  info.latched_fault = link.node_fault();
  const std::uint32_t active = link.ReadU32(fp::param::kActiveSlot);
  info.active_slot = active < 2 ? static_cast<int>(active) : -1;
  for (int k = 0; k < 2; ++k) {
    const std::uint32_t status = link.ReadU32(static_cast<std::uint16_t>(fp::param::kSlotStatus + k));
    info.slot_status[k] = status <= 4 ? static_cast<fp::StorageResult>(status) : fp::StorageResult::BadCrc;
    info.slot_generation[k] = link.ReadU32(static_cast<std::uint16_t>(fp::param::kSlotGeneration + k));
  }
  info.calibration_date_s = link.ReadU32(fp::param::kCalibrationDate_s);
  info.calibration_tool_version = link.ReadU32(fp::param::kCalibrationToolVersion);
  // A node below protocol 1.3 has no stored_layout parameter: all it stores is layout 1.
  if (info.active_slot >= 0)
    info.stored_layout = info.identity.max_minor < fp::kLayout2Minor
                             ? 1
                             : static_cast<std::uint16_t>(link.ReadU32(fp::param::kStoredLayout));
  return info;
}

}  // namespace vesica::device::calibration
