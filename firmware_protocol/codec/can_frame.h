// One CAN or CAN FD frame as it travels on the wire, independent of any OS API.
// Use: fill id/len/data (and set kFdFrame for CAN FD); the codec (codec.h) produces and consumes these,
// and every transport (transport/transport.h) sends and receives them.
// Freestanding C++17: no heap, no exceptions, no OS calls.
#pragma once

#include <cstdint>

namespace vesica::fp {

inline constexpr std::uint8_t kClassicMaxLength = 8;
inline constexpr std::uint8_t kFdMaxLength = 64;

struct CanFrame {
  enum Flags : std::uint8_t {
    kExtendedId = 1u << 0,  // 29-bit identifier (our protocol uses 11-bit only; kept for gateways)
    kFdFrame = 1u << 1,     // CAN FD format (len may be 0..8,12,16,20,24,32,48,64)
    kBitRateSwitch = 1u << 2,  // CAN FD data phase at the data bit rate
    kRemote = 1u << 3,      // classic remote request (never used by our protocol; rejected)
  };
  std::uint32_t id = 0;    // 11-bit (or 29-bit with kExtendedId) identifier
  std::uint8_t len = 0;    // payload bytes
  std::uint8_t flags = 0;  // Flags
  std::uint8_t data[kFdMaxLength] = {};

  constexpr bool extended() const { return (flags & kExtendedId) != 0; }
  constexpr bool fd() const { return (flags & kFdFrame) != 0; }
  constexpr bool brs() const { return (flags & kBitRateSwitch) != 0; }
  constexpr bool remote() const { return (flags & kRemote) != 0; }
};

// Payload lengths a CAN FD frame can carry (DLC 0..15).
constexpr bool is_valid_fd_length(std::uint8_t len) {
  return len <= 8 || len == 12 || len == 16 || len == 20 || len == 24 || len == 32 || len == 48 ||
         len == 64;
}

constexpr bool operator==(const CanFrame& a, const CanFrame& b) {
  if (a.id != b.id || a.len != b.len || a.flags != b.flags) return false;
  for (std::uint8_t i = 0; i < a.len && i < kFdMaxLength; ++i)
    if (a.data[i] != b.data[i]) return false;
  return true;
}
constexpr bool operator!=(const CanFrame& a, const CanFrame& b) { return !(a == b); }

}  // namespace vesica::fp
