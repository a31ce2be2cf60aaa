// Writes frames to a pcap file with link type LINKTYPE_CAN_SOCKETCAN (227), the form Wireshark and
// tshark read SocketCAN captures in: per packet the 8-byte SocketCAN header (id big-endian, length,
// FD flags) and the payload, 16 bytes for classic frames and 72 for CAN FD.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <vector>

#include "firmware_protocol/codec/can_frame.h"

namespace vesica::fp::test {

inline void write_socketcan_pcap(const std::filesystem::path& path, const std::vector<CanFrame>& frames) {
  std::ofstream out(path, std::ios::binary);
  auto le32 = [&](std::uint32_t v) { for (int i = 0; i < 4; ++i) out.put(static_cast<char>(v >> (8 * i))); };
  auto le16 = [&](std::uint16_t v) { for (int i = 0; i < 2; ++i) out.put(static_cast<char>(v >> (8 * i))); };
  le32(0xA1B2C3D4);  // pcap, microsecond timestamps
  le16(2);
  le16(4);
  le32(0);
  le32(0);
  le32(65535);
  le32(227);  // LINKTYPE_CAN_SOCKETCAN
  std::uint32_t seconds = 1700000000;
  for (const CanFrame& f : frames) {
    const bool fd = f.fd() || f.len > kClassicMaxLength;  // a longer frame can only be CAN FD
    const std::uint32_t size = fd ? 72 : 16;
    le32(seconds++);
    le32(0);
    le32(size);
    le32(size);
    std::uint32_t id = f.id;
    if (f.extended()) id |= 0x80000000u;  // CAN_EFF_FLAG
    if (f.remote()) id |= 0x40000000u;    // CAN_RTR_FLAG
    for (int i = 3; i >= 0; --i) out.put(static_cast<char>(id >> (8 * i)));
    out.put(static_cast<char>(f.len));
    out.put(static_cast<char>(fd ? 0x04 | (f.brs() ? 0x01 : 0) : 0));  // CANFD_FDF, CANFD_BRS
    out.put(0);
    out.put(0);
    for (std::uint32_t i = 0; i < size - 8; ++i) out.put(static_cast<char>(i < f.len ? f.data[i] : 0));
  }
}

}  // namespace vesica::fp::test
