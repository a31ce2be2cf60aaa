// CRC-32 (IEEE 802.3, reflected, poly 0xEDB88320) for the stored parameter block.
// Use: crc32(bytes, n); crc32("123456789") == 0xCBF43926. Freestanding C++17, bitwise (no table).
#pragma once

#include <cstddef>
#include <cstdint>

namespace vesica::fp {

constexpr std::uint32_t crc32(const std::uint8_t* data, std::size_t n, std::uint32_t crc = 0) {
  crc = ~crc;
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= data[i];
    for (int b = 0; b < 8; ++b) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

}  // namespace vesica::fp
