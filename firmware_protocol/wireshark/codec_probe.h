// What the codec refuses beyond each field's range, found by asking it: which in-range values of a
// small field are not enumerators (NMT command 3), and which payload bits no field uses must be
// zero (AuxState byte 1 bits 3..7). The dissector generator writes these into the Lua file, so a
// rule added to the codec reaches the dissector without anyone copying it.
// Use: CodecProbe p = probe_codec(MessageKind::Nmt); p.enumerations[0].valid_raw -> {1, 2, 128, ...}
// Host side.
#pragma once

#include <cstdint>
#include <vector>

#include "firmware_protocol/codec/message_table.h"

namespace vesica::fp {

struct FieldEnumeration {
  const FieldSpec* field = nullptr;
  std::vector<std::int64_t> valid_raw;  // the in-range raw values the codec accepts, ascending
};

struct ReservedBits {
  std::uint8_t offset = 0;  // payload byte
  std::uint8_t mask = 0;    // bits the codec requires to be zero
};

struct CodecProbe {
  bool probed = false;  // false when no valid frame of this kind could be made to start from
  std::vector<FieldEnumeration> enumerations;  // only fields where some in-range value is refused
  std::vector<ReservedBits> reserved;
};

// Probes fields whose raw range has at most 256 values, one value at a time, from a valid frame.
CodecProbe probe_codec(MessageKind kind);

}  // namespace vesica::fp
