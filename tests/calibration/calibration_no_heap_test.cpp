// The node's calibration paths stay freestanding: a session with host commands, parameter writes,
// a save into a slot and a boot from the slots allocate nothing (counts global operator new).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "firmware_protocol/node/node.h"
#include "tests/can/fake_node_hardware.h"

namespace {
std::atomic<long> g_allocations{0};
}

void* operator new(std::size_t n) {
  ++g_allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace vesica::fp {
namespace {

TEST(CalibrationNoHeapTest, SessionSaveAndBootAllocateNothing) {
  testing::FakeNodeHardware hw;
  hw.storage.assign(2 * slot::kStride, 0xFF);  // the fake's flash, allocated up front
  Node<testing::FakeNodeHardware> node(hw, 1);
  const long before = g_allocations.load();
  node.boot(0);
  CanFrame f;
  std::uint64_t now_us = 0;
  auto send = [&](const Message& m) {
    encode(m, f);
    node.on_frame(f, now_us);
    CanFrame out;
    while (node.pop_tx(out)) {
    }
  };
  send(CalibrationCommand{1, CalibrationProcedure::Session, 0b111, 0.5f});
  for (int i = 0; i < 100; ++i) {
    now_us += 1000;
    send(CurrentCommand{1, static_cast<std::uint8_t>(i), CommandMode::MotorCurrent, {0.1f, -0.1f, 0.2f}});
    node.tick(now_us);
  }
  send(ParameterRequest{1, ParameterOp::Write, ParameterType::F32, param::kPositionOffset, f32_bits(0.25f)});
  send(ParameterRequest{1, ParameterOp::Save, ParameterType::None, 0, 0});
  node.boot(now_us);
  const long after = g_allocations.load();
  EXPECT_EQ(after - before, 0);
  EXPECT_EQ(node.active_slot(), 0);
  EXPECT_FLOAT_EQ(node.parameters().f32(param::kPositionOffset), 0.25f);
}

}  // namespace
}  // namespace vesica::fp
