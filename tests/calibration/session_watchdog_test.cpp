// The calibration session's watchdog (protocol 1.2, docs/protocol.md section 11): a host that
// negotiated 1.2 may fall silent for up to 250 ms (a loaded host over UDP) without ending the
// session, and a cut bus still stops the motion: the currents are zero 250 ms after the last
// command, the node latches command_watchdog, the session ends and the stored calibration is
// back. A host that negotiated 1.1 keeps the 3 ms watchdog it knows.
#include <gtest/gtest.h>

#include <cmath>

#include "calibration_rig.h"
#include "device/calibration/calibration_abort.h"
#include "firmware_protocol/node/parameter_table.h"

namespace vesica::device::calibration {
namespace {

using testing::CalibrationRig;
constexpr double kWatchdog_s = 0.250;

// Opens a session on yaw and drives it with a small constant current for 0.4 s (it speeds up to
// 1-2 rad/s); returns the bus time of the last command.
double DriveYaw(CalibrationRig& rig) {
  rig.link->BeginSession(0b001, 0.6);
  for (int i = 0; i < 400; ++i) rig.link->Cycle({0.05, 0.0, 0.0});
  return rig.link->now_s();
}

TEST(SessionWatchdogTest, ACutBusStopsTheMotionWithinTheSessionWatchdog) {
  CalibrationRig rig(5);
  ASSERT_GE(rig.link->Connect().negotiated_minor, 2);  // 1.2 or later
  const auto& node = rig.emulator->node();
  const float stored_offset = node.parameters().f32(fp::param::kPositionOffset);
  rig.link->WriteF32(fp::param::kPositionOffset, stored_offset + 0.5f);  // unsaved, in the session below
  const double cut = DriveYaw(rig);
  ASSERT_TRUE(node.calibration_session_open());
  const double speed = std::abs(rig.emulator->plant().qd()[0]);
  EXPECT_GT(speed, 0.5);            // it is moving
  EXPECT_LE(speed, 3.05);           // within the session's speed bound (50 % of 6 rad/s)
  rig.arm_ep.set_connected(false);  // the cable is pulled

  // When the node's watchdog tripped, and that the motor had no current from then on; sampled
  // every 100 us of bus time.
  double tripped_at = -1.0;
  bool current_after_trip = false;
  rig.each_step = [&] {
    if (tripped_at < 0 && node.latched_fault() == fp::FaultCode::CommandWatchdog)
      tripped_at = rig.clock.now().count() * 1e-9;
    if (tripped_at >= 0 && rig.emulator->board().applied_currents() != fp::JointArray{0, 0, 0})
      current_after_trip = true;
  };
  rig.RunUntil(rig.clock.now() + std::chrono::milliseconds(3000));
  ASSERT_GT(tripped_at, 0.0) << "the watchdog never tripped";
  EXPECT_FALSE(current_after_trip);
  // The node's last command arrived within the period before the cut: the watchdog trips after
  // its 250 ms, within a period and a control tick, never before.
  EXPECT_GE(tripped_at - cut, kWatchdog_s - 0.0011);
  EXPECT_LE(tripped_at - cut, kWatchdog_s + 0.0002);
  EXPECT_EQ(node.latched_fault(), fp::FaultCode::CommandWatchdog);
  EXPECT_FALSE(node.calibration_session_open());
  EXPECT_EQ(node.parameters().f32(fp::param::kPositionOffset), stored_offset);  // the stored calibration
  // With no current the joint coasts and friction (or a stop) brings it to rest within 3 s.
  EXPECT_EQ(rig.emulator->plant().qd()[0], 0.0);
}

TEST(SessionWatchdogTest, SilencesShorterThanTheWatchdogKeepTheSessionOpen) {
  CalibrationRig rig(6);
  ASSERT_GE(rig.link->Connect().negotiated_minor, 2);  // 1.2 or later
  DriveYaw(rig);
  // A stalled host: no command for 200 ms, then commands again.
  rig.RunUntil(rig.clock.now() + std::chrono::milliseconds(200));
  try {
    for (int i = 0; i < 50; ++i) rig.link->Cycle({0.0, 0.0, 0.0});
  } catch (const CalibrationAbort& e) {
    FAIL() << e.what();
  }
  EXPECT_TRUE(rig.emulator->node().calibration_session_open());
  EXPECT_EQ(rig.emulator->node().latched_fault(), fp::FaultCode::None);
  rig.link->AbortSession();
}

TEST(SessionWatchdogTest, AHostThatNegotiatedProtocol1Point1KeepsTheThreeMillisecondWatchdog) {
  CalibrationRig rig(7);
  rig.link->Connect();
  // Hello from a 1.1 host: the node negotiates 1.1.
  fp::CanFrame f;
  ASSERT_EQ(fp::encode(fp::Hello{1, fp::kProtocolMajor, 1}, f), fp::EncodeError::None);
  rig.tool_ep.send(f, rig.clock.now() + std::chrono::milliseconds(1));
  rig.RunUntil(rig.clock.now() + std::chrono::milliseconds(5));
  ASSERT_EQ(rig.emulator->node().negotiated_minor(), 1);
  DriveYaw(rig);
  rig.RunUntil(rig.clock.now() + std::chrono::milliseconds(5));  // more than 3 ms without a command
  EXPECT_EQ(rig.emulator->node().latched_fault(), fp::FaultCode::CommandWatchdog);
  EXPECT_FALSE(rig.emulator->node().calibration_session_open());
}

}  // namespace
}  // namespace vesica::device::calibration
