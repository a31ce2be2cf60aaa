// Frame length on the wire: exact for classic frames (stuffed as transmitted), bounded for CAN FD.
#include "firmware_protocol/codec/frame_timing.h"

namespace vesica::fp {
namespace {

// Bits SOF..data of a classic data frame, unstuffed, with the CRC-15 appended.
struct BitBuffer {
  std::uint8_t bits[160] = {};
  std::uint32_t n = 0;
  void push(std::uint32_t value, std::uint32_t width) {
    for (std::uint32_t i = width; i-- > 0;) bits[n++] = static_cast<std::uint8_t>((value >> i) & 1u);
  }
};

std::uint32_t crc15(const BitBuffer& b) {
  std::uint32_t crc = 0;
  for (std::uint32_t i = 0; i < b.n; ++i) {
    const std::uint32_t next = b.bits[i] ^ ((crc >> 14) & 1u);
    crc = (crc << 1) & 0x7FFFu;
    if (next) crc ^= 0x4599u;
  }
  return crc;
}

}  // namespace

std::uint32_t classic_exact_bits(const CanFrame& frame) {
  const std::uint8_t len = frame.len > 8 ? 8 : frame.len;
  BitBuffer b;
  b.push(0, 1);  // SOF
  if (frame.extended()) {
    b.push(frame.id >> 18, 11);
    b.push(1, 1);  // SRR
    b.push(1, 1);  // IDE
    b.push(frame.id & 0x3FFFFu, 18);
    b.push(frame.remote() ? 1 : 0, 1);
    b.push(0, 2);  // r1, r0
  } else {
    b.push(frame.id & 0x7FFu, 11);
    b.push(frame.remote() ? 1 : 0, 1);
    b.push(0, 2);  // IDE, r0
  }
  b.push(len, 4);
  if (!frame.remote())
    for (std::uint8_t i = 0; i < len; ++i) b.push(frame.data[i], 8);
  b.push(crc15(b), 15);
  // Count stuff bits: after five equal bits the transmitter inserts the complement, which itself
  // starts the next run.
  std::uint32_t stuffed = 0, run = 1;
  std::uint8_t last = b.bits[0];
  for (std::uint32_t i = 1; i < b.n; ++i) {
    if (b.bits[i] == last) {
      if (++run == 5) {
        ++stuffed;
        last = static_cast<std::uint8_t>(!last);
        run = 1;
      }
    } else {
      last = b.bits[i];
      run = 1;
    }
  }
  return b.n + stuffed + 1 /*CRC delim*/ + 2 /*ACK slot + delim*/ + 7 /*EOF*/ + 3 /*IFS*/;
}

namespace {
// CAN FD worst case, standard id: arbitration fields and tail at the nominal rate, the rest at the
// data rate (when BRS). Dynamic stuffing bound before the CRC field, fixed stuff bits in it.
void fd_bits(std::uint8_t payload, std::uint32_t& nominal, std::uint32_t& data) {
  const std::uint32_t arb = 1 + 11 + 1 + 1 + 1 + 1 + 1;  // SOF id RRS IDE FDF res BRS
  nominal = arb + (arb - 1) / 4 + 1 /*CRC delim*/ + 2 /*ACK*/ + 7 /*EOF*/ + 3 /*IFS*/;
  const std::uint32_t ctrl_data = 1 /*ESI*/ + 4 /*DLC*/ + 8u * payload;
  const std::uint32_t crc = payload <= 16 ? 17 : 21;
  const std::uint32_t crc_field = 4 /*stuff count*/ + crc;
  data = ctrl_data + (ctrl_data - 1) / 4 + crc_field + (crc_field + 3) / 4;
}
}  // namespace

std::uint64_t fd_worst_case_duration_ns(std::uint8_t payload, const BitRates& rates) {
  std::uint32_t nominal = 0, data = 0;
  fd_bits(payload, nominal, data);
  return 1'000'000'000ull * nominal / rates.nominal_bps + 1'000'000'000ull * data / rates.data_bps;
}

std::uint64_t frame_duration_ns(const CanFrame& frame, const BitRates& rates, bool worst_case) {
  if (frame.fd()) {
    std::uint32_t nominal = 0, data = 0;
    fd_bits(frame.len, nominal, data);
    const std::uint32_t data_bps = frame.brs() ? rates.data_bps : rates.nominal_bps;
    return 1'000'000'000ull * nominal / rates.nominal_bps + 1'000'000'000ull * data / data_bps;
  }
  const std::uint32_t bits = worst_case ? classic_worst_case_bits(frame.len, frame.extended()) : classic_exact_bits(frame);
  return 1'000'000'000ull * bits / rates.nominal_bps;
}

}  // namespace vesica::fp
