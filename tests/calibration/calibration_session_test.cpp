// The node's calibration session (protocol 1.1): the host drives the motors inside a bound; a
// Save keeps what it wrote, anything else (abort, watchdog, E-stop, NMT) brings the stored
// calibration back. Also what the node does with the calibration it runs on.
#include <gtest/gtest.h>

#include <vector>

#include "firmware_protocol/node/node.h"
#include "tests/can/fake_node_hardware.h"

namespace vesica::fp {
namespace {

using testing::FakeNodeHardware;

class CalibrationSessionTest : public ::testing::Test {
 protected:
  FakeNodeHardware hw;
  Node<FakeNodeHardware> node{hw, 0x5E55};
  std::uint64_t now_us = 0;
  std::uint8_t counter = 0;

  void SetUp() override { node.boot(0); }
  std::vector<Message> Send(const Message& m) {
    CanFrame f;
    EXPECT_EQ(encode(m, f), EncodeError::None);
    node.on_frame(f, now_us);
    return Drain();
  }
  std::vector<Message> Drain() {
    std::vector<Message> out;
    CanFrame f;
    while (node.pop_tx(f)) {
      Message m;
      if (decode(f, m) == DecodeError::None) out.push_back(m);
    }
    return out;
  }
  void Tick(int n = 1) {
    for (int i = 0; i < n; ++i) {
      now_us += 1000;
      node.tick(now_us);
    }
  }
  void Command(float a0, float a1, float a2) {
    Send(CurrentCommand{1, counter++, CommandMode::MotorCurrent, {a0, a1, a2}});
  }
  ParameterResponse Parameter(ParameterOp op, std::uint16_t index, ParameterType type = ParameterType::None,
                              std::uint32_t raw = 0) {
    for (const Message& m : Send(ParameterRequest{1, op, type, index, raw}))
      if (const auto* r = std::get_if<ParameterResponse>(&m)) return *r;
    ADD_FAILURE() << "no response";
    return {};
  }
  std::vector<CalibrationProgress> Progress(const std::vector<Message>& ms) {
    std::vector<CalibrationProgress> out;
    for (const Message& m : ms)
      if (const auto* p = std::get_if<CalibrationProgress>(&m)) out.push_back(*p);
    return out;
  }
  void Begin(std::uint8_t mask = 0b111, float max_current = 0.5f) {
    const auto p = Progress(Send(CalibrationCommand{1, CalibrationProcedure::Session, mask, max_current}));
    ASSERT_EQ(p.size(), 1u);
    ASSERT_EQ(p[0].status, CalibrationStatus::Running);
    ASSERT_TRUE(node.calibration_session_open());
  }
  void StoreOffset(float v) {
    ASSERT_FALSE(Parameter(ParameterOp::Write, param::kPositionOffset, ParameterType::F32, f32_bits(v)).aborted);
    ASSERT_FALSE(Parameter(ParameterOp::Save, 0).aborted);
  }
};

TEST_F(CalibrationSessionTest, HostCurrentsAreBoundedAndTheJointRangeDoesNotApply) {
  Begin(0b011, 0.5f);
  hw.sample.position = {2.5f, -2.5f, 0.1f};  // far outside joint_min/max (+-1 rad)
  Tick();
  Command(2.0f, -2.0f, 1.0f);
  Tick();
  EXPECT_EQ(hw.applied, (JointArray{0.5f, -0.5f, 0.0f}));  // insertion is not in the mask
  EXPECT_EQ(node.latched_fault(), FaultCode::None);        // no joint_range_exceeded
  EXPECT_FALSE(node.enabled());
  EXPECT_EQ(node.state(), NodeState::PreOperational);
}

TEST_F(CalibrationSessionTest, SaveKeepsWhatTheSessionWroteAndEndsItDone) {
  StoreOffset(0.1f);
  Begin();
  Command(0, 0, 0);
  ASSERT_FALSE(Parameter(ParameterOp::Write, param::kPositionOffset, ParameterType::F32, f32_bits(0.3f)).aborted);
  const auto ms = Send(ParameterRequest{1, ParameterOp::Save, ParameterType::None, 0, 0});
  const auto p = Progress(ms);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].procedure, CalibrationProcedure::Session);
  EXPECT_EQ(p[0].status, CalibrationStatus::Done);
  EXPECT_FALSE(node.calibration_session_open());
  Node<FakeNodeHardware> rebooted(hw, 0x5E55);
  rebooted.boot(0);
  EXPECT_FLOAT_EQ(rebooted.parameters().f32(param::kPositionOffset), 0.3f);
}

TEST_F(CalibrationSessionTest, AbortBringsTheStoredCalibrationBack) {
  StoreOffset(0.1f);
  Begin();
  Command(0.4f, 0, 0);
  Tick();
  ASSERT_FALSE(Parameter(ParameterOp::Write, param::kPositionOffset, ParameterType::F32, f32_bits(0.3f)).aborted);
  const auto p = Progress(Send(CalibrationCommand{1, CalibrationProcedure::Abort, 0, 0.0f}));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].status, CalibrationStatus::Aborted);
  EXPECT_FALSE(node.calibration_session_open());
  EXPECT_FLOAT_EQ(node.parameters().f32(param::kPositionOffset), 0.1f);
  EXPECT_EQ(hw.applied, (JointArray{0, 0, 0}));
}

TEST_F(CalibrationSessionTest, ASilentHostTripsTheWatchdogAndTheStoredCalibrationIsBack) {
  StoreOffset(0.1f);
  Begin();
  ASSERT_FALSE(Parameter(ParameterOp::Write, param::kPositionOffset, ParameterType::F32, f32_bits(0.3f)).aborted);
  Command(0.4f, 0, 0);
  Tick();
  EXPECT_FLOAT_EQ(hw.applied[0], 0.4f);
  Tick(4);  // more than the 3 ms watchdog without a command
  EXPECT_EQ(node.latched_fault(), FaultCode::CommandWatchdog);
  EXPECT_FALSE(node.calibration_session_open());
  EXPECT_EQ(hw.applied, (JointArray{0, 0, 0}));
  EXPECT_FLOAT_EQ(node.parameters().f32(param::kPositionOffset), 0.1f);
}

TEST_F(CalibrationSessionTest, AWriteArrivingAfterAFaultIsRefused) {
  StoreOffset(0.1f);
  Begin();
  Send(EStop{0});
  EXPECT_EQ(hw.applied, (JointArray{0, 0, 0}));  // at once
  Tick();                                        // the session ends at the next control tick
  EXPECT_FALSE(node.calibration_session_open());
  const ParameterResponse r = Parameter(ParameterOp::Write, param::kPositionOffset, ParameterType::F32, f32_bits(0.3f));
  EXPECT_TRUE(r.aborted);
  EXPECT_EQ(r.raw_value, static_cast<std::uint32_t>(AbortCode::WrongState));
  EXPECT_FLOAT_EQ(node.parameters().f32(param::kPositionOffset), 0.1f);
}

TEST_F(CalibrationSessionTest, EnableIsRefusedAndNmtStartEndsTheSession) {
  Send(Hello{1, kProtocolMajor, kProtocolMinor});
  Begin();
  Send(Control{1, 0, ControlCommand::Enable});
  EXPECT_FALSE(node.enabled());
  const auto p = Progress(Send(Nmt{NmtCommand::Start, 1}));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].status, CalibrationStatus::Aborted);
  EXPECT_FALSE(node.calibration_session_open());
  EXPECT_EQ(node.state(), NodeState::Operational);
}

TEST_F(CalibrationSessionTest, RefusedWhenOperationalOrAlreadyOpen) {
  Begin();
  auto p = Progress(Send(CalibrationCommand{1, CalibrationProcedure::Session, 0b111, 0.5f}));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].status, CalibrationStatus::Failed);
  EXPECT_TRUE(node.calibration_session_open());  // the open one goes on
  Send(CalibrationCommand{1, CalibrationProcedure::Abort, 0, 0.0f});
  Send(Nmt{NmtCommand::Start, 1});
  p = Progress(Send(CalibrationCommand{1, CalibrationProcedure::Session, 0b111, 0.5f}));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].status, CalibrationStatus::Failed);
}

TEST_F(CalibrationSessionTest, TheDriveGetsTheCurrentOffsetAddedAndZeroStaysZero) {
  ASSERT_FALSE(Parameter(ParameterOp::Write, param::kCurrentOffset + 1, ParameterType::F32, f32_bits(0.05f)).aborted);
  Begin();
  Command(0, 0.3f, 0);
  Tick();
  EXPECT_FLOAT_EQ(hw.applied[1], 0.35f);  // the sensor reads 0.05 A high: the loop aims 0.05 higher
  EXPECT_EQ(hw.applied[0], 0.0f);
  EXPECT_FLOAT_EQ(node.applied_current()[1], 0.3f);  // what the motor gets
}

TEST_F(CalibrationSessionTest, AReversedEncoderIsTurnedRoundBeforeTheOffset) {
  ASSERT_FALSE(
      Parameter(ParameterOp::Write, param::kEncoderDirection + 0, ParameterType::I32, static_cast<std::uint32_t>(-1))
          .aborted);
  ASSERT_FALSE(Parameter(ParameterOp::Write, param::kPositionOffset + 0, ParameterType::F32, f32_bits(0.2f)).aborted);
  hw.sample.position = {0.5f, 0, 0.1f};
  hw.sample.velocity = {1.0f, 0, 0};
  Tick();
  std::vector<JointState> js;
  for (const Message& m : Send(Sync{0}))
    if (const auto* p = std::get_if<JointState>(&m)) js.push_back(*p);
  ASSERT_EQ(js.size(), 1u);
  EXPECT_NEAR(js[0].position[0], -0.3f, 1e-4);
  EXPECT_EQ(Parameter(ParameterOp::Write, param::kEncoderDirection, ParameterType::I32, 2).raw_value,
            static_cast<std::uint32_t>(AbortCode::ValueTooHigh));
}

}  // namespace
}  // namespace vesica::fp
