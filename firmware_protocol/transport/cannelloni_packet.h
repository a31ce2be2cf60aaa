// cannelloni UDP packet format, version 2 (github.com/mguentner/cannelloni, doc/udp_format.md):
//   header: version u8 (=2), op_code u8 (0 = DATA), seq_no u8, count u16 big-endian
//   per frame: can_id u32 big-endian with Linux EFF/RTR/ERR flag bits, len u8 (| 0x80 for CAN FD),
//              flags u8 (CAN FD only), data[len] (none for RTR frames)
// Use: std::size_t n = write_cannelloni_packet(frames, count, seq, buf, cap);
//      parse_cannelloni_packet(buf, n, on_frame) -> CannelloniError (malformed packets never crash).
#pragma once

#include <cstddef>
#include <cstdint>

#include "firmware_protocol/codec/can_frame.h"

namespace vesica::fp {

inline constexpr std::uint8_t kCannelloniVersion = 2;
inline constexpr std::uint8_t kCannelloniOpData = 0;
inline constexpr std::size_t kCannelloniHeaderSize = 5;
inline constexpr std::uint8_t kCannelloniFdFlag = 0x80;
inline constexpr std::uint32_t kLinuxEffFlag = 0x80000000u;
inline constexpr std::uint32_t kLinuxRtrFlag = 0x40000000u;
inline constexpr std::uint32_t kLinuxErrFlag = 0x20000000u;
inline constexpr std::uint8_t kLinuxFdBrs = 0x01;  // CANFD_BRS

enum class CannelloniError : std::uint8_t { None, Truncated, BadVersion, BadOpCode, BadLength, TrailingBytes };
const char* to_string(CannelloniError e);

// Bytes one frame takes in a packet.
std::size_t cannelloni_frame_size(const CanFrame& f);

// Writes a DATA packet with `count` frames; returns its size, 0 if it does not fit `capacity`.
std::size_t write_cannelloni_packet(const CanFrame* frames, std::size_t count, std::uint8_t seq_no,
                                    std::uint8_t* out, std::size_t capacity);

// Parses a packet, calling sink(frame) for each frame (error frames included, with their Linux id
// in frame.id and kLinuxErrFlag kept). Stops at the first malformed frame and reports why.
template <class Sink>
CannelloniError parse_cannelloni_packet(const std::uint8_t* p, std::size_t n, std::uint8_t& seq_no, Sink&& sink);

// ---- implementation ----
namespace cannelloni_detail {
CannelloniError parse_frame(const std::uint8_t*& p, const std::uint8_t* end, CanFrame& f);
}

template <class Sink>
CannelloniError parse_cannelloni_packet(const std::uint8_t* p, std::size_t n, std::uint8_t& seq_no, Sink&& sink) {
  if (n < kCannelloniHeaderSize) return CannelloniError::Truncated;
  if (p[0] != kCannelloniVersion) return CannelloniError::BadVersion;
  if (p[1] != kCannelloniOpData) return CannelloniError::BadOpCode;
  seq_no = p[2];
  const std::size_t count = static_cast<std::size_t>(p[3]) << 8 | p[4];
  const std::uint8_t* cur = p + kCannelloniHeaderSize;
  const std::uint8_t* end = p + n;
  for (std::size_t i = 0; i < count; ++i) {
    CanFrame f;
    const CannelloniError e = cannelloni_detail::parse_frame(cur, end, f);
    if (e != CannelloniError::None) return e;
    sink(f);
  }
  return cur == end ? CannelloniError::None : CannelloniError::TrailingBytes;
}

}  // namespace vesica::fp
