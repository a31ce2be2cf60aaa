// Parameter values of one node, checked against parameter_table.h, and their persistent image:
// magic, version, count, the persistent values, CRC-32 over all preceding bytes.
// Use: ParameterStore s; s.write(index, type, raw) -> AbortCode; s.f32(index);
//      s.serialize(buf) / s.deserialize(buf, n) -> StorageResult (CRC checked).
// Freestanding C++17: fixed arrays, no heap.
#pragma once

#include <cstddef>
#include <cstdint>

#include "firmware_protocol/node/parameter_table.h"

namespace vesica::fp {

enum class StorageResult : std::uint8_t { Ok, BadMagic, BadVersion, BadSize, BadCrc };
const char* to_string(StorageResult r);

class ParameterStore {
 public:
  static constexpr std::uint32_t kMagic = 0x31505356;  // "VSP1"
  // Layout 2 (protocol 1.3) is written; layout 1 (1.0 .. 1.2: the table's first
  // kLayout1ParameterCount parameters) is still read, the parameters it lacks at their defaults.
  static constexpr std::uint16_t kLayoutVersion = 2;
  static constexpr std::size_t kImageSize = 4 + 2 + 2 + 4 * kParameterCount + 4;
  static constexpr std::size_t kLayout1ImageSize = 4 + 2 + 2 + 4 * kLayout1ParameterCount + 4;
  // Image bytes of a layout (0: a layout this firmware does not know).
  static constexpr std::size_t image_size_of_layout(std::uint16_t layout) {
    return layout == 1 ? kLayout1ImageSize : layout == 2 ? kImageSize : 0;
  }

  ParameterStore() { restore_defaults(); }
  void restore_defaults();

  // Host-facing write: checks existence, access, type, range. Read-only values are set with set_internal.
  AbortCode write(std::uint16_t index, ParameterType type, std::uint32_t raw);
  AbortCode read(std::uint16_t index, ParameterType& type, std::uint32_t& raw) const;

  // Node-internal access (no access check; range still enforced for F32/U32 by clamping is NOT done:
  // callers pass valid values). Returns false for an unknown index.
  bool set_internal(std::uint16_t index, std::uint32_t raw);
  bool set_internal_f32(std::uint16_t index, float v);

  float f32(std::uint16_t index) const;
  std::uint32_t u32(std::uint16_t index) const;

  // Image of the persistent parameters (non-persistent slots are written as their defaults), in
  // layout 2, or in layout 1 for a node that emulates firmware older than protocol 1.3.
  std::size_t serialize(std::uint8_t* out, std::size_t capacity, std::uint16_t layout = kLayoutVersion) const;
  // Loads a layout-1 or layout-2 image (n: the bytes available); layout, when given, receives the
  // image's layout. A layout-1 image leaves the parameters it lacks at their defaults.
  StorageResult deserialize(const std::uint8_t* in, std::size_t n, std::uint16_t* layout = nullptr);

 private:
  std::uint32_t raw_[kParameterCount] = {};
};

std::uint32_t f32_bits(float v);
float bits_f32(std::uint32_t raw);

}  // namespace vesica::fp
