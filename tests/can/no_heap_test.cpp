// The codec and the reference node never touch the heap on the hot path (docs/architecture.md:
// freestanding firmware code). Counts global operator new calls around 1000 control cycles.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "firmware_protocol/codec/codec.h"
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

TEST(NoHeapTest, CodecAndNodeCyclesAllocateNothing) {
  testing::FakeNodeHardware hw;
  hw.storage.reserve(ParameterStore::kImageSize);  // the fake's own buffer, allocated up front
  Node<testing::FakeNodeHardware> node(hw, 1);
  node.boot(0);
  CanFrame f;
  encode(Hello{1, kProtocolMajor, kProtocolMinor}, f);
  node.on_frame(f, 0);
  encode(Nmt{NmtCommand::Start, 0}, f);
  node.on_frame(f, 0);
  encode(Control{1, 0, ControlCommand::Enable}, f);
  node.on_frame(f, 0);
  const long before = g_allocations.load();
  ASSERT_GT(before, 0) << "operator new replacement not in effect";
  std::uint64_t now_us = 0;
  for (int i = 0; i < 1000; ++i) {
    now_us += 1000;
    encode(CurrentCommand{1, static_cast<std::uint8_t>(i), CommandMode::JointTorque, {0.1f, -0.1f, 0.5f}}, f);
    node.on_frame(f, now_us);
    node.tick(now_us);
    CanFrame out;
    Message m;
    while (node.pop_tx(out)) decode(out, m);
  }
  encode(ParameterRequest{1, ParameterOp::Read, ParameterType::None, param::kMaxCurrent, 0}, f);
  node.on_frame(f, now_us);
  encode(ParameterRequest{1, ParameterOp::Save, ParameterType::None, 0, 0}, f);
  encode(Control{1, 1, ControlCommand::Disable}, f);
  node.on_frame(f, now_us);
  node.tick(now_us + 1000);
  const long after = g_allocations.load();
  EXPECT_EQ(after - before, 0);
  EXPECT_TRUE(node.latched_fault() == FaultCode::None);
}

}  // namespace
}  // namespace vesica::fp
