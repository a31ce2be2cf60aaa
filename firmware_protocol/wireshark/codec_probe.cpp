// Starts from each message's default struct (node 1), encoded; changes one field value or one
// unused bit at a time and keeps what decode() calls OutOfRange. Changes that make fields disagree
// (Inconsistent) are not range rules and are not reported here.
#include "firmware_protocol/wireshark/codec_probe.h"

#include <utility>

#include "firmware_protocol/codec/codec.h"
#include "firmware_protocol/wireshark/field_bits.h"

namespace vesica::fp {
namespace {

template <std::size_t... I>
Message default_message(std::size_t index, std::index_sequence<I...>) {
  Message m;
  ((index == I ? (void)m.emplace<I>() : void()), ...);
  std::visit([](auto& v) {
    if constexpr (requires { v.node; }) v.node = 1;
  }, m);
  return m;
}

bool refused_as_out_of_range(const CanFrame& f) {
  Message m;
  return decode(f, m) == DecodeError::OutOfRange;
}

}  // namespace

CodecProbe probe_codec(MessageKind kind) {
  CodecProbe probe;
  CanFrame base;
  const Message m = default_message(static_cast<std::size_t>(kind), std::make_index_sequence<std::variant_size_v<Message>>{});
  if (encode(m, base) != EncodeError::None) return probe;
  Message check;
  if (decode(base, check) != DecodeError::None) return probe;
  probe.probed = true;

  std::uint8_t used[kFdMaxLength] = {};
  for (const FieldSpec* f : kAllFields) {
    if (f->message != kind) continue;
    for (std::uint8_t i = 0; i < wire_size(f->type); ++i) used[f->offset + i] |= field_byte_mask(*f, i);
    const std::int64_t lo = raw_min(*f), hi = raw_max(*f);
    if (hi - lo >= 256) continue;
    FieldEnumeration e{f, {}};
    for (std::int64_t raw = lo; raw <= hi; ++raw) {
      CanFrame probe_frame = base;
      write_field_raw(probe_frame, *f, raw);
      if (!refused_as_out_of_range(probe_frame)) e.valid_raw.push_back(raw);
    }
    if (static_cast<std::int64_t>(e.valid_raw.size()) != hi - lo + 1) probe.enumerations.push_back(std::move(e));
  }
  for (std::uint8_t byte = 0; byte < spec_of(kind).length; ++byte) {
    std::uint8_t mask = 0;
    for (int bit = 0; bit < 8; ++bit) {
      if (used[byte] & (1u << bit)) continue;
      CanFrame probe_frame = base;
      probe_frame.data[byte] = static_cast<std::uint8_t>(probe_frame.data[byte] ^ (1u << bit));
      if (refused_as_out_of_range(probe_frame)) mask = static_cast<std::uint8_t>(mask | (1u << bit));
    }
    if (mask) probe.reserved.push_back({byte, mask});
  }
  return probe;
}

}  // namespace vesica::fp
