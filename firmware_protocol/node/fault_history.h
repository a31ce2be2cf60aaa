// Latched fault plus a short history of past faults, newest first (like CiA 301 object 0x1003).
// Use: raise(code, joint, detail) latches the first fault; clear() on fault reset; entry(k) packs
// code | joint << 8 | (uint16)detail << 16 for the read-only parameters fault_history[k].
// Freestanding C++17.
#pragma once

#include <cstdint>

#include "firmware_protocol/codec/protocol_enums.h"
#include "firmware_protocol/node/parameter_table.h"

namespace vesica::fp {

class FaultHistory {
 public:
  // Records the fault; returns true if it is the newly latched one (no fault was latched before).
  bool raise(FaultCode code, std::uint8_t joint, std::int16_t detail) {
    for (int k = param::kFaultHistoryDepth - 1; k > 0; --k) entries_[k] = entries_[k - 1];
    entries_[0] = pack(code, joint, detail);
    if (count_ < 0xFFFFFFFFu) ++count_;
    if (latched_ != FaultCode::None) return false;
    latched_ = code;
    return true;
  }
  void clear_latch() { latched_ = FaultCode::None; }
  void relatch(FaultCode code) { latched_ = code; }  // keep a latch across a node reset, no new entry
  FaultCode latched() const { return latched_; }
  std::uint32_t count() const { return count_; }
  std::uint32_t entry(int k) const { return entries_[k]; }
  void restore(std::uint32_t count, const std::uint32_t* entries) {
    count_ = count;
    for (int k = 0; k < param::kFaultHistoryDepth; ++k) entries_[k] = entries[k];
  }

  static constexpr std::uint32_t pack(FaultCode code, std::uint8_t joint, std::int16_t detail) {
    return static_cast<std::uint32_t>(code) | (static_cast<std::uint32_t>(joint) << 8) |
           (static_cast<std::uint32_t>(static_cast<std::uint16_t>(detail)) << 16);
  }

 private:
  FaultCode latched_ = FaultCode::None;
  std::uint32_t count_ = 0;
  std::uint32_t entries_[param::kFaultHistoryDepth] = {};
};

}  // namespace vesica::fp
