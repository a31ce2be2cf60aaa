// Virtual bus: exact frame timing, arbitration by identifier, deadlines, error injection, bus load.
#include "firmware_protocol/transport/virtual_bus.h"

#include <gtest/gtest.h>

using namespace std::chrono_literals;

namespace vesica::fp {
namespace {

CanFrame frame(std::uint32_t id, std::uint8_t len, std::uint8_t fill = 0xA5) {
  CanFrame f;
  f.id = id;
  f.len = len;
  for (int i = 0; i < len; ++i) f.data[i] = static_cast<std::uint8_t>(fill + i);
  return f;
}

TEST(VirtualBusTest, FrameArrivesAtItsExactEndOfFrameTime) {
  VirtualClock clock;
  VirtualBus bus(clock);
  auto& a = bus.attach("a");
  auto& b = bus.attach("b");
  const CanFrame f = frame(0x181, 8);
  ASSERT_EQ(a.send(f, 1ms), SendStatus::Queued);
  const auto expected_end = Nanoseconds{1000ll * classic_exact_bits(f)};
  bus.run_until(expected_end - 1ns);
  TimedFrame rx;
  EXPECT_FALSE(b.receive(rx));  // still on the wire
  bus.run_until(expected_end);
  ASSERT_TRUE(b.receive(rx));
  EXPECT_EQ(rx.frame, f);
  EXPECT_EQ(rx.timestamp, expected_end);
  EXPECT_FALSE(a.receive(rx));  // no echo to the sender
}

TEST(VirtualBusTest, SenderUnpluggedMidFrameLosesTheFrame) {
  // Was undefined behaviour (the finished frame was popped from the emptied queue): a double
  // free in the calibration's bus-loss test.
  VirtualClock clock;
  VirtualBus bus(clock);
  auto& a = bus.attach("a");
  auto& b = bus.attach("b");
  const CanFrame f = frame(0x181, 8);
  ASSERT_EQ(a.send(f, 1ms), SendStatus::Queued);
  bus.run_until(Nanoseconds{1000ll * classic_exact_bits(f) / 2});  // half on the wire
  a.set_connected(false);
  bus.run_until(1ms);
  TimedFrame rx;
  EXPECT_FALSE(b.receive(rx));
  EXPECT_EQ(a.stats().tx_frames, 0u);
  ASSERT_EQ(b.send(frame(0x182, 2), 2ms), SendStatus::Queued);  // the bus goes on
  bus.run_until(2ms);
  EXPECT_EQ(b.stats().tx_frames, 1u);
}

TEST(VirtualBusTest, LowestIdentifierWinsArbitration) {
  VirtualClock clock;
  VirtualBus bus(clock);
  auto& a = bus.attach("a");
  auto& b = bus.attach("b");
  auto& c = bus.attach("c");
  auto& listener = bus.attach("listener");
  ASSERT_EQ(a.send(frame(0x300, 2), 10ms), SendStatus::Queued);
  ASSERT_EQ(b.send(frame(0x001, 2), 10ms), SendStatus::Queued);
  ASSERT_EQ(c.send(frame(0x181, 2), 10ms), SendStatus::Queued);
  bus.advance(5ms);
  std::vector<std::uint32_t> order;
  TimedFrame rx;
  while (listener.receive(rx)) order.push_back(rx.frame.id);
  EXPECT_EQ(order, (std::vector<std::uint32_t>{0x001, 0x181, 0x300}));
}

TEST(VirtualBusTest, FramesQueuedDuringATransmissionWaitForTheBus) {
  VirtualClock clock;
  VirtualBus bus(clock);
  auto& a = bus.attach("a");
  auto& b = bus.attach("b");
  auto& listener = bus.attach("listener");
  const CanFrame first = frame(0x500, 8), second = frame(0x100, 8);
  a.send(first, 1ms);
  bus.advance(10us);  // first is on the wire now
  b.send(second, 1ms);
  bus.advance(1ms);
  TimedFrame r1, r2;
  ASSERT_TRUE(listener.receive(r1));
  ASSERT_TRUE(listener.receive(r2));
  EXPECT_EQ(r1.frame.id, 0x500u);  // no pre-emption despite the higher priority
  EXPECT_EQ(r2.timestamp, r1.timestamp + Nanoseconds{1000ll * classic_exact_bits(second)});
}

TEST(VirtualBusTest, FrameThatCannotStartBeforeItsDeadlineIsDropped) {
  VirtualClock clock;
  VirtualBus bus(clock);
  auto& a = bus.attach("a");
  auto& b = bus.attach("b");
  auto& listener = bus.attach("listener");
  a.send(frame(0x100, 8), 1ms);
  b.send(frame(0x200, 8), 50us);  // loses arbitration; bus busy ~130 us
  bus.advance(1ms);
  TimedFrame rx;
  ASSERT_TRUE(listener.receive(rx));
  EXPECT_FALSE(listener.receive(rx));
  EXPECT_EQ(b.stats().tx_dropped, 1u);
  BusEvent ev;
  ASSERT_TRUE(b.poll_event(ev));
  EXPECT_EQ(ev.kind, BusEvent::Kind::TxDropped);
  EXPECT_EQ(ev.detail, 0x200u);
  EXPECT_EQ(a.send(frame(0x100, 1), clock.now() - 1ns), SendStatus::DeadlineMissed);
}

TEST(VirtualBusTest, InjectedErrorsAreRetransmittedAndMoveErrorCounters) {
  VirtualClock clock;
  VirtualBus bus(clock);
  auto& a = bus.attach("a");
  auto& b = bus.attach("b");
  bus.inject_errors(2);
  a.send(frame(0x181, 8), 10ms);
  bus.advance(2ms);
  TimedFrame rx;
  ASSERT_TRUE(b.receive(rx));  // delivered on the third attempt
  EXPECT_FALSE(b.receive(rx));
  EXPECT_EQ(bus.error_frames(), 2u);
  EXPECT_EQ(a.transmit_error_counter(), 2 * 8 - 1);  // +8 per error, -1 per success
  EXPECT_EQ(a.stats().error_frames, 2u);
  // 16 consecutive errors: TEC 128 -> error passive; 32 -> bus-off, queue dropped.
  VirtualClock clock2;
  VirtualBus bus2(clock2);
  auto& tx = bus2.attach("tx");
  bus2.attach("rx");
  bus2.inject_errors(32);
  tx.send(frame(0x181, 8), 1s);
  bus2.advance(100ms);
  EXPECT_EQ(tx.state(), BusState::BusOff);
  EXPECT_EQ(tx.send(frame(0x181, 8), clock2.now() + 1ms), SendStatus::BusOff);
  std::vector<BusState> states;
  BusEvent ev;
  while (tx.poll_event(ev))
    if (ev.kind == BusEvent::Kind::StateChanged) states.push_back(ev.state);
  EXPECT_EQ(states, (std::vector<BusState>{BusState::ErrorWarning, BusState::ErrorPassive, BusState::BusOff}));
}

TEST(VirtualBusTest, BusLoadIsBusyTimeOverElapsedTime) {
  VirtualClock clock;
  VirtualBus bus(clock);
  auto& a = bus.attach("a");
  bus.attach("b");
  bus.reset_load();
  std::int64_t busy_ns = 0;
  for (int ms = 0; ms < 100; ++ms) {
    const CanFrame f = frame(0x181, 8, static_cast<std::uint8_t>(ms));
    busy_ns += 1000ll * classic_exact_bits(f);
    a.send(f, clock.now() + 1ms);
    bus.advance(1ms);
  }
  EXPECT_NEAR(bus.load(), busy_ns / 100e6, 1e-12);
  EXPECT_EQ(bus.frames_transmitted(), 100u);
}

TEST(VirtualBusTest, UnpluggedEndpointReportsDeviceLostAndRefusesToSend) {
  VirtualClock clock;
  VirtualBus bus(clock);
  auto& a = bus.attach("a");
  auto& b = bus.attach("b");
  b.set_connected(false);
  BusEvent ev;
  ASSERT_TRUE(b.poll_event(ev));
  EXPECT_EQ(ev.kind, BusEvent::Kind::DeviceLost);
  EXPECT_EQ(b.send(frame(0x1, 2), 1ms), SendStatus::Closed);
  a.send(frame(0x181, 8), 1ms);
  bus.advance(1ms);
  TimedFrame rx;
  EXPECT_FALSE(b.receive(rx));
  b.set_connected(true);
  EXPECT_EQ(b.state(), BusState::ErrorActive);
}

TEST(VirtualBusTest, CanFdFrameUsesTheDataBitRateAndInvalidLengthsAreRefused) {
  VirtualClock clock;
  VirtualBus bus(clock);
  auto& a = bus.attach("a");
  auto& b = bus.attach("b");
  CanFrame f = frame(0x181, 0);
  f.flags = CanFrame::kFdFrame | CanFrame::kBitRateSwitch;
  f.len = 64;
  ASSERT_EQ(a.send(f, 1ms), SendStatus::Queued);
  bus.advance(1ms);
  TimedFrame rx;
  ASSERT_TRUE(b.receive(rx));
  EXPECT_EQ(rx.timestamp, Nanoseconds{static_cast<std::int64_t>(fd_worst_case_duration_ns(64, BitRates{}))});
  EXPECT_LT(rx.timestamp, 200us);  // 64 bytes at 5 Mbit/s: far below 8 classic frames (1080 us)
  f.len = 9;  // not an FD length
  EXPECT_EQ(a.send(f, clock.now() + 1ms), SendStatus::Invalid);
  CanFrame classic = frame(0x181, 8);
  classic.len = 12;
  EXPECT_EQ(a.send(classic, clock.now() + 1ms), SendStatus::Invalid);
}

TEST(VirtualBusTest, ReceiveQueueOverflowIsCounted) {
  VirtualClock clock;
  VirtualBus::Config cfg;
  cfg.rx_queue_depth = 4;
  VirtualBus bus(clock, cfg);
  auto& a = bus.attach("a");
  auto& b = bus.attach("b");
  for (int i = 0; i < 6; ++i) a.send(frame(0x100 + i, 1), 10ms);
  bus.advance(5ms);
  EXPECT_EQ(b.stats().rx_frames, 4u);
  EXPECT_EQ(b.stats().rx_dropped, 2u);
}

}  // namespace
}  // namespace vesica::fp
