// The logging transport on the virtual bus: every frame the host sends and receives is in the log,
// in order, with the transport's timestamps; refused frames are not logged.
#include "firmware_protocol/buslog/logging_transport.h"

#include <gtest/gtest.h>

#include <sstream>

#include "firmware_protocol/buslog/bus_log_reader.h"
#include "firmware_protocol/codec/codec.h"
#include "firmware_protocol/transport/virtual_bus.h"

using namespace std::chrono_literals;

namespace vesica::fp {
namespace {

CanFrame encoded(const Message& m) {
  CanFrame f;
  EXPECT_EQ(encode(m, f), EncodeError::None);
  return f;
}

TEST(LoggingTransportTest, LogsSentFramesAtSendTimeAndReceivedFramesAtTheirTimestamp) {
  VirtualClock clock;
  VirtualBus bus(clock);
  auto& host_port = bus.attach("host");
  auto& arm = bus.attach("arm");
  std::stringstream text;
  BusLogWriter writer(text);
  LoggingTransport host(host_port, writer, "can0");

  bus.advance(1ms);
  const CanFrame hello = encoded(Hello{1, 1, 0});
  ASSERT_EQ(host.send(hello, host.now() + 1ms), SendStatus::Queued);
  bus.advance(1ms);
  const CanFrame identity = encoded(Identity{1, kProtocolMajor, 0, 0, 0, 1234});
  ASSERT_EQ(arm.send(identity, arm.now() + 1ms), SendStatus::Queued);
  bus.advance(1ms);
  TimedFrame rx;
  ASSERT_TRUE(host.receive(rx));
  EXPECT_FALSE(host.receive(rx));

  std::vector<BusLogEntry> log;
  std::string error;
  ASSERT_TRUE(read_bus_log(text, log, error)) << error;
  ASSERT_EQ(log.size(), 2u);
  EXPECT_EQ(log[0].timestamp, 1ms);
  EXPECT_EQ(log[0].interface, "can0");
  EXPECT_EQ(log[0].frame, hello);
  EXPECT_EQ(log[1].timestamp, std::chrono::duration_cast<std::chrono::microseconds>(rx.timestamp));
  EXPECT_GT(log[1].timestamp, 2ms);  // the end of the frame on the wire, after it was queued
  EXPECT_EQ(log[1].frame, identity);
  EXPECT_EQ(text.str().substr(0, 35), "(0000000000.001000) can0 681#0100\n(");
}

TEST(LoggingTransportTest, FrameTheTransportRefusesIsNotLogged) {
  VirtualClock clock;
  VirtualBus bus(clock);
  auto& port = bus.attach("host");
  std::stringstream text;
  BusLogWriter writer(text);
  LoggingTransport host(port, writer, "can0");
  port.set_connected(false);
  const CanFrame sync = encoded(Sync{7});
  EXPECT_NE(host.send(sync, host.now() + 1ms), SendStatus::Queued);
  EXPECT_EQ(writer.lines_written(), 0u);
  EXPECT_EQ(text.str(), "");
}

TEST(LoggingTransportTest, InterfaceNameIsCheckedWhenTheTapIsMade) {
  VirtualClock clock;
  VirtualBus bus(clock);
  auto& port = bus.attach("host");
  std::stringstream text;
  BusLogWriter writer(text);
  EXPECT_THROW(LoggingTransport(port, writer, "can 0"), std::invalid_argument);
  EXPECT_THROW(LoggingTransport(port, writer, ""), std::invalid_argument);
}

}  // namespace
}  // namespace vesica::fp
