// SocketCAN error frames map to bus states as linux/can/error.h defines them. Reference values are
// the kernel's constants written out, so a wrong header mapping would show.
#include "firmware_protocol/transport/socketcan_error_frame.h"

#include <gtest/gtest.h>

namespace vesica::fp {
namespace {

constexpr std::uint32_t kErrFlag = 0x20000000;
constexpr std::uint32_t kCrtl = 0x00000004, kBusOff = 0x00000040, kRestarted = 0x00000100;
constexpr std::uint8_t kRxWarning = 0x04, kTxPassive = 0x20, kRxOverflow = 0x01, kActive = 0x40;

TEST(SocketCanErrorFrameTest, ControllerStatesMapToBusStates) {
  std::uint8_t d[8] = {};
  d[1] = kRxWarning;
  auto e = interpret_error_frame(kErrFlag | kCrtl, d);
  ASSERT_TRUE(e.has_state);
  EXPECT_EQ(e.state, BusState::ErrorWarning);
  d[1] = kTxPassive | kRxWarning;  // passive wins over warning
  e = interpret_error_frame(kErrFlag | kCrtl, d);
  EXPECT_EQ(e.state, BusState::ErrorPassive);
  d[1] = kActive;
  e = interpret_error_frame(kErrFlag | kCrtl, d);
  EXPECT_EQ(e.state, BusState::ErrorActive);
  d[1] = kRxOverflow;
  e = interpret_error_frame(kErrFlag | kCrtl, d);
  EXPECT_FALSE(e.has_state);
  EXPECT_TRUE(e.overflow);
}

TEST(SocketCanErrorFrameTest, BusOffAndRestart) {
  const std::uint8_t d[8] = {};
  auto e = interpret_error_frame(kErrFlag | kBusOff, d);
  ASSERT_TRUE(e.has_state);
  EXPECT_EQ(e.state, BusState::BusOff);
  EXPECT_EQ(e.error_class, kBusOff);
  e = interpret_error_frame(kErrFlag | kRestarted, d);
  EXPECT_EQ(e.state, BusState::ErrorActive);
  e = interpret_error_frame(kErrFlag | 0x00000008 /* protocol violation */, d);
  EXPECT_FALSE(e.has_state);
  EXPECT_EQ(e.error_class, 0x8u);
}

}  // namespace
}  // namespace vesica::fp
