// Bandwidth budget of docs/protocol.md, computed from the codec's real frames: two arms at 1 kHz on
// classic CAN 1 Mbit/s stay at or under 60 % worst-case load; the virtual bus measures the same mix.
#include <gtest/gtest.h>

#include "firmware_protocol/codec/codec.h"
#include "firmware_protocol/codec/frame_timing.h"
#include "firmware_protocol/node/node.h"
#include "firmware_protocol/transport/virtual_bus.h"
#include "tests/can/fake_node_hardware.h"

using namespace std::chrono_literals;

namespace vesica::fp {
namespace {

constexpr int kArms = 2;

// Worst-case bus time per second of every cyclic message in operation, for kArms nodes.
double worst_case_load(bool fd) {
  const BitRates rates;
  double busy_ns_per_s = 0;
  for (const MessageSpec& s : kMessageSpecs) {
    if (s.rate_hz == 0 || !s.per_node) continue;
    if (s.kind == MessageKind::CalibrationProgress) continue;  // only in pre-operational calibration
    const std::uint64_t ns = fd ? fd_worst_case_duration_ns(s.length, rates)
                                : 1000ull * classic_worst_case_bits(s.length);
    busy_ns_per_s += static_cast<double>(kArms) * s.rate_hz * static_cast<double>(ns);
  }
  return busy_ns_per_s / 1e9;
}

TEST(BandwidthBudgetTest, ClassicCanWorstCaseLoadAtMostSixtyPercent) {
  const double load = worst_case_load(false);
  // 2 x (CurrentCommand + JointState) x 1 kHz x 135 us = 54 %, + AuxState/CurrentState 100 Hz
  // (5.4 %) + 3-byte heartbeat 10 Hz (0.17 %) = 59.57 %.
  EXPECT_NEAR(load, 0.5957, 0.0001);
  EXPECT_LE(load, 0.60);
}

TEST(BandwidthBudgetTest, CanFdWithBitRateSwitchHalvesTheLoad) {
  const double load = worst_case_load(true);
  EXPECT_LT(load, 0.35);
  EXPECT_LT(load, worst_case_load(false) / 1.8);
}

TEST(BandwidthBudgetTest, VirtualBusMeasuresTwoArmsBelowTheWorstCase) {
  VirtualClock clock;
  VirtualBus bus(clock);
  auto& host = bus.attach("host");
  testing::FakeNodeHardware hw[kArms];
  Node<testing::FakeNodeHardware> node0(hw[0], 1), node1(hw[1], 2);
  Node<testing::FakeNodeHardware>* nodes[kArms] = {&node0, &node1};
  VirtualBusEndpoint* ep[kArms] = {&bus.attach("arm1"), &bus.attach("arm2")};
  for (int a = 0; a < kArms; ++a) {
    // Node id 2 for the second arm through the parameter block.
    ParameterStore p;
    p.set_internal(param::kNodeId, static_cast<std::uint32_t>(a + 1));
    hw[a].storage.resize(ParameterStore::kImageSize);
    p.serialize(hw[a].storage.data(), hw[a].storage.size());
    hw[a].sample.position = {0.1f * a, -0.2f, 0.05f};
    nodes[a]->boot(0);
  }
  auto pump_nodes = [&] {
    for (int a = 0; a < kArms; ++a) {
      TimedFrame rx;
      while (ep[a]->receive(rx)) nodes[a]->on_frame(rx.frame, static_cast<std::uint64_t>(clock.now().count() / 1000));
      CanFrame f;
      while (nodes[a]->pop_tx(f)) ep[a]->send(f, clock.now() + 1ms);
    }
  };
  for (int a = 0; a < kArms; ++a) {
    CanFrame f;
    encode(Hello{static_cast<std::uint8_t>(a + 1), kProtocolMajor, kProtocolMinor}, f);
    host.send(f, clock.now() + 1ms);
  }
  CanFrame start;
  encode(Nmt{NmtCommand::Start, 0}, start);
  host.send(start, clock.now() + 1ms);
  bus.advance(1ms);
  pump_nodes();
  bus.advance(1ms);
  bus.reset_load();
  std::uint8_t counter = 0;
  for (int ms = 0; ms < 1000; ++ms) {
    for (int a = 0; a < kArms; ++a) {
      CanFrame f;
      encode(CurrentCommand{static_cast<std::uint8_t>(a + 1), counter, CommandMode::MotorCurrent,
                            {0.25f * static_cast<float>(ms % 7), -0.5f, 1.0f}}, f);
      host.send(f, clock.now() + 1ms);
    }
    ++counter;
    for (int sub = 0; sub < 4; ++sub) {  // nodes answer within the cycle
      bus.advance(250us);
      pump_nodes();
      for (int a = 0; a < kArms; ++a) nodes[a]->tick(static_cast<std::uint64_t>(clock.now().count() / 1000));
    }
    TimedFrame rx;
    while (host.receive(rx)) {}
  }
  const double measured = bus.load();
  RecordProperty("measured_load", std::to_string(measured));
  EXPECT_GT(measured, 0.35);  // the cyclic traffic really ran
  EXPECT_LT(measured, worst_case_load(false));
  EXPECT_EQ(host.stats().tx_dropped, 0u);
}

}  // namespace
}  // namespace vesica::fp
