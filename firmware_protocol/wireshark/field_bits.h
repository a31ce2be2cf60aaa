// A field's raw value in a frame, read and written exactly as the codec does it (little-endian,
// bit fields inside one byte), from its FieldSpec alone.
// Use: by the dissector generator's codec probe and by tests that build frames field by field.
// Host side.
#pragma once

#include <cstdint>

#include "firmware_protocol/codec/can_frame.h"
#include "firmware_protocol/codec/message_table.h"

namespace vesica::fp {

constexpr std::int64_t raw_of(double si, double lsb) {
  const double x = si / lsb;
  return static_cast<std::int64_t>(x < 0 ? x - 0.5 : x + 0.5);
}
// The field's valid raw range, as the codec rounds it.
constexpr std::int64_t raw_min(const FieldSpec& f) { return raw_of(f.min, f.lsb); }
constexpr std::int64_t raw_max(const FieldSpec& f) { return raw_of(f.max, f.lsb); }

constexpr bool is_signed(WireType t) { return t == WireType::I8 || t == WireType::I16 || t == WireType::I32; }

// Bits of byte `offset + i` the field occupies.
constexpr std::uint8_t field_byte_mask(const FieldSpec& f, std::uint8_t i) {
  if (f.bit_width == 0) return i < wire_size(f.type) ? 0xFF : 0;
  return i == 0 ? static_cast<std::uint8_t>(((1u << f.bit_width) - 1u) << f.bit_offset) : 0;
}

inline std::int64_t read_field_raw(const CanFrame& frame, const FieldSpec& f) {
  std::uint32_t u = 0;
  for (std::uint8_t i = 0; i < wire_size(f.type); ++i) u |= static_cast<std::uint32_t>(frame.data[f.offset + i]) << (8 * i);
  if (f.bit_width != 0) return (u >> f.bit_offset) & ((1u << f.bit_width) - 1u);
  switch (f.type) {
    case WireType::I8: return static_cast<std::int8_t>(u);
    case WireType::I16: return static_cast<std::int16_t>(u);
    case WireType::I32: return static_cast<std::int32_t>(u);
    default: return u;
  }
}

// Replaces the field's bits with `raw` (two's complement for negative values), nothing else.
inline void write_field_raw(CanFrame& frame, const FieldSpec& f, std::int64_t raw) {
  if (f.bit_width != 0) {
    const std::uint8_t mask = field_byte_mask(f, 0);
    frame.data[f.offset] = static_cast<std::uint8_t>((frame.data[f.offset] & ~mask) |
                                                     ((static_cast<std::uint32_t>(raw) << f.bit_offset) & mask));
    return;
  }
  const auto u = static_cast<std::uint32_t>(raw);
  for (std::uint8_t i = 0; i < wire_size(f.type); ++i) frame.data[f.offset + i] = static_cast<std::uint8_t>(u >> (8 * i));
}

}  // namespace vesica::fp
