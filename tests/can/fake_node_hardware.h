// A scriptable board for node tests: sensor values set by the test, applied currents and the
// storage image recorded.
#pragma once

#include <cstring>
#include <vector>

#include "firmware_protocol/node/node_hardware.h"
#include "firmware_protocol/node/parameter_store.h"

namespace vesica::fp::testing {

struct FakeNodeHardware {
  HardwareSample sample;
  JointArray applied{};
  int apply_calls = 0;
  std::vector<std::uint8_t> storage;  // empty: blank flash; offset 0 = slot A
  bool storage_write_fails = false;

  HardwareSample sense() { return sample; }
  void apply_currents(const JointArray& amps) { applied = amps; ++apply_calls; }
  bool storage_read(std::size_t offset, std::uint8_t* dst, std::size_t n) {
    if (storage.size() < offset + n) return false;
    std::memcpy(dst, storage.data() + offset, n);
    return true;
  }
  bool storage_write(std::size_t offset, const std::uint8_t* src, std::size_t n) {
    if (storage_write_fails) return false;
    if (storage.size() < offset + n) storage.resize(offset + n, 0xFF);  // erased flash reads 0xFF
    std::memcpy(storage.data() + offset, src, n);
    return true;
  }
};

#if defined(__cpp_concepts)
static_assert(NodeHardware<FakeNodeHardware>);
#endif

}  // namespace vesica::fp::testing
