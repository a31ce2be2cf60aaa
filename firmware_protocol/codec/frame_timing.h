// Time a frame occupies the bus: exact bit count of a real frame (with its actual stuff bits and
// CRC) for classic CAN, and the worst-case stuffing bound (Davis et al. 2007) for budgets.
// Use: frame_bits_exact(f) * bit time gives the virtual bus's transmission time;
//      worst_case_bits(...) feeds the bandwidth budget in docs/protocol.md.
// Freestanding C++17.
#pragma once

#include <cstdint>

#include "firmware_protocol/codec/can_frame.h"

namespace vesica::fp {

struct BitRates {
  std::uint32_t nominal_bps = 1'000'000;  // arbitration phase
  std::uint32_t data_bps = 5'000'000;     // CAN FD data phase (used when the frame has BRS)
};

// Worst-case bits of a classic frame with `payload` bytes, including the 3-bit interframe space.
// Standard id: 47 + 8s + floor((34 + 8s - 1) / 4); extended id: 67 + 8s + floor((54 + 8s - 1)/4).
constexpr std::uint32_t classic_worst_case_bits(std::uint8_t payload, bool extended = false) {
  const std::uint32_t s = payload;
  return extended ? 67 + 8 * s + (54 + 8 * s - 1) / 4 : 47 + 8 * s + (34 + 8 * s - 1) / 4;
}

// Exact bit count of this classic frame on the wire: SOF..CRC stuffed as transmitted, plus CRC
// delimiter, ACK slot and delimiter, EOF (7) and interframe space (3).
std::uint32_t classic_exact_bits(const CanFrame& frame);

// Bus time of a frame in nanoseconds. Classic: exact bits. CAN FD: worst-case bound with the
// arbitration part at nominal rate and the data part at the data rate when BRS is set.
std::uint64_t frame_duration_ns(const CanFrame& frame, const BitRates& rates, bool worst_case = false);

// CAN FD worst-case duration (ns) for a payload size, standard id, with BRS.
std::uint64_t fd_worst_case_duration_ns(std::uint8_t payload, const BitRates& rates);

}  // namespace vesica::fp
