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
  std::vector<std::uint8_t> storage;  // empty: blank flash
  bool storage_write_fails = false;

  HardwareSample sense() { return sample; }
  void apply_currents(const JointArray& amps) { applied = amps; ++apply_calls; }
  bool storage_read(std::uint8_t* dst, std::size_t n) {
    if (storage.size() < n) return false;
    std::memcpy(dst, storage.data(), n);
    return true;
  }
  bool storage_write(const std::uint8_t* src, std::size_t n) {
    if (storage_write_fails) return false;
    storage.assign(src, src + n);
    return true;
  }
};

#if defined(__cpp_concepts)
static_assert(NodeHardware<FakeNodeHardware>);
#endif

}  // namespace vesica::fp::testing
