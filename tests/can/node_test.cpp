// Reference firmware node: state machine, enable, watchdog, limits, E-stop, faults, parameters, calibration.
#include "firmware_protocol/node/node.h"
#include "firmware_protocol/node/crc32.h"

#include <gtest/gtest.h>

#include <vector>

#include "tests/can/fake_node_hardware.h"

namespace vesica::fp {
namespace {

using testing::FakeNodeHardware;
constexpr std::uint8_t kNode = 1;

class NodeTest : public ::testing::Test {
 protected:
  FakeNodeHardware hw;
  Node<FakeNodeHardware> node{hw, 0xABCD};
  std::uint64_t now_us = 0;
  std::uint8_t counter = 0;
  std::uint8_t control_counter = 0;

  void SetUp() override { node.boot(now_us); }

  void send(const Message& m) {
    CanFrame f;
    ASSERT_EQ(encode(m, f), EncodeError::None);
    node.on_frame(f, now_us);
  }
  std::vector<Message> drain() {
    std::vector<Message> out;
    CanFrame f;
    while (node.pop_tx(f)) {
      Message m;
      EXPECT_EQ(decode(f, m), DecodeError::None) << "node sent an undecodable frame id " << f.id;
      out.push_back(m);
    }
    return out;
  }
  template <class T>
  std::vector<T> sent(const std::vector<Message>& ms) {
    std::vector<T> out;
    for (const Message& m : ms)
      if (auto* p = std::get_if<T>(&m)) out.push_back(*p);
    return out;
  }
  void step(std::uint64_t dt_us = 1000) {
    now_us += dt_us;
    node.tick(now_us);
  }
  void command(float a0, float a1, float a2, CommandMode mode = CommandMode::MotorCurrent) {
    send(CurrentCommand{kNode, counter++, mode, {a0, a1, a2}});
  }
  void bring_up() {
    send(Hello{kNode, kProtocolMajor, kProtocolMinor});
    send(Nmt{NmtCommand::Start, 0});
    send(Control{kNode, control_counter++, ControlCommand::Enable});
    drain();
    ASSERT_EQ(node.state(), NodeState::Operational);
    ASSERT_TRUE(node.enabled());
  }
  ParameterResponse parameter(ParameterOp op, std::uint16_t index, ParameterType type = ParameterType::None,
                              std::uint32_t raw = 0) {
    drain();
    send(ParameterRequest{kNode, op, type, index, raw});
    auto r = sent<ParameterResponse>(drain());
    EXPECT_EQ(r.size(), 1u);
    return r.empty() ? ParameterResponse{} : r[0];
  }
};

TEST_F(NodeTest, BootSendsBootUpHeartbeatAndIdentityThenIsPreOperational) {
  Node<FakeNodeHardware> fresh(hw, 77);
  fresh.boot(0);
  CanFrame f;
  ASSERT_TRUE(fresh.pop_tx(f));
  EXPECT_EQ(f.id, 0x701u);
  EXPECT_EQ(f.data[0], 0x00);  // CANopen boot-up
  ASSERT_TRUE(fresh.pop_tx(f));
  Message m;
  ASSERT_EQ(decode(f, m), DecodeError::None);
  EXPECT_EQ(std::get<Identity>(m).serial, 77u);
  EXPECT_EQ(std::get<Identity>(m).negotiated_minor, 0xFF);
  EXPECT_EQ(fresh.state(), NodeState::PreOperational);
  EXPECT_EQ(fresh.latched_fault(), FaultCode::None);  // blank flash is a new board, not a fault
}

TEST_F(NodeTest, NmtMovesBetweenStates) {
  send(Nmt{NmtCommand::Start, 0});
  EXPECT_EQ(node.state(), NodeState::Operational);
  send(Nmt{NmtCommand::Stop, 2});  // another node: ignored
  EXPECT_EQ(node.state(), NodeState::Operational);
  send(Nmt{NmtCommand::Stop, kNode});
  EXPECT_EQ(node.state(), NodeState::Stopped);
  send(Nmt{NmtCommand::EnterPreOperational, 0});
  EXPECT_EQ(node.state(), NodeState::PreOperational);
}

TEST_F(NodeTest, EnableNeedsOperationalAndNegotiatedProtocol) {
  send(Control{kNode, 0, ControlCommand::Enable});
  EXPECT_FALSE(node.enabled());  // pre-operational
  send(Nmt{NmtCommand::Start, 0});
  send(Control{kNode, 1, ControlCommand::Enable});
  EXPECT_FALSE(node.enabled());  // no Hello yet
  send(Hello{kNode, static_cast<std::uint8_t>(kProtocolMajor + 1), 0});
  EXPECT_EQ(node.negotiated_minor(), 0xFF);  // wrong major
  send(Hello{kNode, kProtocolMajor, 7});
  EXPECT_EQ(node.negotiated_minor(), kProtocolMinor);  // highest minor both speak
  send(Control{kNode, 2, ControlCommand::Enable});
  EXPECT_TRUE(node.enabled());
}

TEST_F(NodeTest, DisabledNodeAppliesNoCurrentButAnswersCommands) {
  send(Nmt{NmtCommand::Start, 0});
  drain();
  command(1.0f, 1.0f, 1.0f);
  auto js = sent<JointState>(drain());
  ASSERT_EQ(js.size(), 1u);
  EXPECT_FALSE(js[0].enabled);
  step();
  EXPECT_EQ(hw.applied, (JointArray{0, 0, 0}));
  EXPECT_EQ(node.active_limiter(), Limiter::Disabled);
}

TEST_F(NodeTest, EnabledNodeAppliesCommandedCurrent) {
  bring_up();
  command(0.5f, -0.25f, 1.0f);
  step();
  EXPECT_FLOAT_EQ(hw.applied[0], 0.5f);
  EXPECT_FLOAT_EQ(hw.applied[1], -0.25f);
  EXPECT_FLOAT_EQ(hw.applied[2], 1.0f);
  EXPECT_EQ(node.active_limiter(), Limiter::None);
}

TEST_F(NodeTest, JointTorqueModeDividesByTorqueConstantTimesGear) {
  bring_up();
  command(0.2f, 0, 0, CommandMode::JointTorque);
  step();
  const float nm_per_A = node.parameters().f32(param::kTorqueConstant) * node.parameters().f32(param::kGearRatio);
  EXPECT_NEAR(hw.applied[0], 0.2f / nm_per_A, 1e-5);
}

TEST_F(NodeTest, CurrentAndTorqueLimitsSaturateAndAreReported) {
  bring_up();
  // Default yaw: max_current 3 A, max_torque 1.2 N·m with 0.0302*14 N·m/A -> 2.838 A.
  command(2.9f, 0, 0);
  step();
  const float torque_amps = 1.2f / (0.0302f * 14.0f);
  EXPECT_NEAR(hw.applied[0], torque_amps, 1e-4);
  EXPECT_EQ(node.active_limiter(), Limiter::Torque);
  command(0, 0, -9.0f);  // insertion: 5 A current limit is below its 10 N / (0.0276*100) = 3.62 A? no: torque first
  step();
  EXPECT_NEAR(hw.applied[2], -10.0f / (0.0276f * 100.0f), 1e-4);
  // Raise the torque limit so the current limit is the one that acts.
  send(Control{kNode, control_counter++, ControlCommand::Disable});
  EXPECT_EQ(parameter(ParameterOp::Write, param::kMaxTorque, ParameterType::F32, f32_bits(100.0f)).aborted, false);
  send(Control{kNode, control_counter++, ControlCommand::Enable});
  command(-4.0f, 0, 0);
  step();
  EXPECT_FLOAT_EQ(hw.applied[0], -3.0f);
  EXPECT_EQ(node.active_limiter(), Limiter::Current);
  auto js = sent<JointState>(drain());
  ASSERT_FALSE(js.empty());
  command(-4.0f, 0, 0);
  step();
  command(-4.0f, 0, 0);  // the reply carries the limiter of the last tick
  js = sent<JointState>(drain());
  ASSERT_FALSE(js.empty());
  EXPECT_EQ(js.back().limiter, Limiter::Current);
}

TEST_F(NodeTest, VelocityLimitRemovesOnlyAcceleratingCurrent) {
  bring_up();
  hw.sample.velocity = {7.0f, 0, 0};  // above the 6 rad/s limit, below the 12 rad/s overspeed fault
  command(1.0f, 0, 0);
  step();
  EXPECT_EQ(hw.applied[0], 0.0f);
  EXPECT_EQ(node.active_limiter(), Limiter::Velocity);
  command(-1.0f, 0, 0);  // braking is allowed
  step();
  EXPECT_FLOAT_EQ(hw.applied[0], -1.0f);
}

TEST_F(NodeTest, JointRangeLimitBlocksPushingFurtherOut) {
  bring_up();
  hw.sample.position = {1.05f, 0, 0.1f};  // beyond yaw max 1.0 rad, inside the 10 % fault margin
  command(0.5f, 0, 0);
  step();
  EXPECT_EQ(hw.applied[0], 0.0f);
  EXPECT_EQ(node.active_limiter(), Limiter::JointRange);
  command(-0.5f, 0, 0);
  step();
  EXPECT_FLOAT_EQ(hw.applied[0], -0.5f);
}

TEST_F(NodeTest, WatchdogZeroesTorqueLatchesFaultAndSendsEmcy) {
  bring_up();
  for (int i = 0; i < 5; ++i) {
    command(1.0f, 1.0f, 1.0f);
    step();
  }
  drain();
  EXPECT_FLOAT_EQ(hw.applied[0], 1.0f);
  // Host stops: default watchdog 3 ms. Tick at 1 kHz until the node reacts.
  int ticks = 0;
  while (node.latched_fault() == FaultCode::None && ticks < 20) { step(); ++ticks; }
  EXPECT_EQ(node.latched_fault(), FaultCode::CommandWatchdog);
  EXPECT_LE(ticks, 4);  // > 3 ms silent is detected on the 4th tick
  EXPECT_EQ(hw.applied, (JointArray{0, 0, 0}));
  EXPECT_EQ(node.state(), NodeState::Fault);
  EXPECT_FALSE(node.enabled());
  auto emcy = sent<Emergency>(drain());
  ASSERT_EQ(emcy.size(), 1u);
  EXPECT_EQ(emcy[0].fault, FaultCode::CommandWatchdog);
  EXPECT_EQ(emcy[0].history_count, 1);
  // Commands alone do not recover.
  command(1.0f, 1.0f, 1.0f);
  step();
  EXPECT_EQ(hw.applied, (JointArray{0, 0, 0}));
  send(Control{kNode, control_counter++, ControlCommand::Enable});
  EXPECT_FALSE(node.enabled());
  // Fault reset clears the latch (EMCY "no error"), then an explicit enable is needed.
  send(Control{kNode, control_counter++, ControlCommand::FaultReset});
  EXPECT_EQ(node.state(), NodeState::Operational);
  EXPECT_FALSE(node.enabled());
  emcy = sent<Emergency>(drain());
  ASSERT_EQ(emcy.size(), 1u);
  EXPECT_EQ(emcy[0].fault, FaultCode::None);
  send(Control{kNode, control_counter++, ControlCommand::Enable});
  command(0.3f, 0, 0);
  step();
  EXPECT_FLOAT_EQ(hw.applied[0], 0.3f);
  EXPECT_EQ(FaultHistory::pack(FaultCode::CommandWatchdog, 0xFF, 0) & 0xFFFF, node.parameters().u32(param::kFaultHistory) & 0xFFFF);
}

TEST_F(NodeTest, EStopFrameAndInputLatchAndBlockReset) {
  bring_up();
  command(1.0f, 0, 0);
  step();
  send(EStop{0});
  EXPECT_EQ(hw.applied, (JointArray{0, 0, 0}));  // immediately, not at the next tick
  EXPECT_EQ(node.latched_fault(), FaultCode::EmergencyStop);
  send(Control{kNode, control_counter++, ControlCommand::FaultReset});
  EXPECT_EQ(node.latched_fault(), FaultCode::None);
  hw.sample.estop_input = true;
  step();
  EXPECT_EQ(node.latched_fault(), FaultCode::EmergencyStop);
  send(Control{kNode, control_counter++, ControlCommand::FaultReset});
  EXPECT_EQ(node.latched_fault(), FaultCode::EmergencyStop);  // loop still open
  hw.sample.estop_input = false;
  step();
  send(Control{kNode, control_counter++, ControlCommand::FaultReset});
  EXPECT_EQ(node.latched_fault(), FaultCode::None);
}

TEST_F(NodeTest, SensorFaultsLatchWithJointAndDetail) {
  bring_up();
  drain();
  hw.sample.current = {0, 8.0f, 0};  // pitch 8 A > 1.5 * 3 A
  step();
  EXPECT_EQ(node.latched_fault(), FaultCode::OverCurrent);
  auto emcy = sent<Emergency>(drain());
  ASSERT_EQ(emcy.size(), 1u);
  EXPECT_EQ(emcy[0].joint, 1);
  EXPECT_EQ(emcy[0].detail, 8000);
  hw.sample.current = {0, 0, 0};
  send(Control{kNode, control_counter++, ControlCommand::FaultReset});
  hw.sample.bus_V = 5.0f;
  step();
  EXPECT_EQ(node.latched_fault(), FaultCode::UnderVoltage);
}

TEST_F(NodeTest, StoppedNodeIgnoresCommandsAndParameters) {
  send(Nmt{NmtCommand::Stop, 0});
  drain();
  command(1.0f, 0, 0);
  send(ParameterRequest{kNode, ParameterOp::Read, ParameterType::None, param::kNodeId, 0});
  EXPECT_TRUE(drain().empty());
}

TEST_F(NodeTest, GarbageAndRepeatedCountersAreCountedNotObeyed) {
  bring_up();
  CanFrame junk;
  junk.id = 0x201;
  junk.len = 3;
  node.on_frame(junk, now_us);
  EXPECT_EQ(node.decode_errors()[DecodeError::WrongLength], 1u);
  send(CurrentCommand{kNode, 10, CommandMode::MotorCurrent, {0.5f, 0, 0}});
  send(CurrentCommand{kNode, 10, CommandMode::MotorCurrent, {2.0f, 0, 0}});  // replay
  step();
  EXPECT_FLOAT_EQ(hw.applied[0], 0.5f);
  EXPECT_EQ(node.decode_errors()[DecodeError::BadCounter], 1u);
  EXPECT_EQ(parameter(ParameterOp::Read, param::kDecodeErrorCount).raw_value, 2u);
}

TEST_F(NodeTest, ParameterChannelAbortsWithCanopenCodes) {
  EXPECT_EQ(parameter(ParameterOp::Read, 0x7777).raw_value, static_cast<std::uint32_t>(AbortCode::NoSuchParameter));
  EXPECT_EQ(parameter(ParameterOp::Write, param::kSerial, ParameterType::U32, 5).raw_value,
            static_cast<std::uint32_t>(AbortCode::ReadOnly));
  EXPECT_EQ(parameter(ParameterOp::Write, param::kMaxCurrent, ParameterType::U32, 5).raw_value,
            static_cast<std::uint32_t>(AbortCode::TypeMismatch));
  EXPECT_EQ(parameter(ParameterOp::Write, param::kMaxCurrent, ParameterType::F32, f32_bits(31.0f)).raw_value,
            static_cast<std::uint32_t>(AbortCode::ValueTooHigh));
  EXPECT_EQ(parameter(ParameterOp::Write, param::kWatchdogTimeout_us, ParameterType::U32, 10).raw_value,
            static_cast<std::uint32_t>(AbortCode::ValueTooLow));
  const ParameterResponse ok = parameter(ParameterOp::Write, param::kMaxCurrent, ParameterType::F32, f32_bits(2.5f));
  EXPECT_FALSE(ok.aborted);
  const ParameterResponse rd = parameter(ParameterOp::Read, param::kMaxCurrent);
  EXPECT_EQ(rd.type, ParameterType::F32);
  EXPECT_FLOAT_EQ(bits_f32(rd.raw_value), 2.5f);
  EXPECT_EQ(parameter(ParameterOp::Read, param::kSerial).raw_value, 0xABCDu);
  bring_up();
  EXPECT_EQ(parameter(ParameterOp::Write, param::kMaxCurrent, ParameterType::F32, f32_bits(1.0f)).raw_value,
            static_cast<std::uint32_t>(AbortCode::WrongState));  // never under torque
}

TEST_F(NodeTest, SavedParametersSurviveRebootAndCorruptionLatchesFault) {
  EXPECT_FALSE(parameter(ParameterOp::Write, param::kWatchdogTimeout_us, ParameterType::U32, 4500).aborted);
  EXPECT_FALSE(parameter(ParameterOp::Save, 0).aborted);
  ASSERT_EQ(hw.storage.size(), slot::kSize);  // the first save goes to slot A
  Node<FakeNodeHardware> rebooted(hw, 0xABCD);
  rebooted.boot(0);
  EXPECT_EQ(rebooted.parameters().u32(param::kWatchdogTimeout_us), 4500u);
  EXPECT_EQ(rebooted.latched_fault(), FaultCode::None);

  hw.storage[20] ^= 0x01;  // one flipped bit
  Node<FakeNodeHardware> corrupted(hw, 0xABCD);
  corrupted.boot(0);
  EXPECT_EQ(corrupted.latched_fault(), FaultCode::ParameterCrc);
  EXPECT_EQ(corrupted.parameters().u32(param::kWatchdogTimeout_us), 3000u);  // defaults

  hw.storage_write_fails = true;
  EXPECT_EQ(parameter(ParameterOp::Save, 0).raw_value, static_cast<std::uint32_t>(AbortCode::StorageFailed));
}

TEST_F(NodeTest, ParameterImageCrcMatchesIndependentCrc32) {
  EXPECT_EQ(crc32(reinterpret_cast<const std::uint8_t*>("123456789"), 9), 0xCBF43926u);  // IEEE check value
  ParameterStore s;
  std::uint8_t image[ParameterStore::kImageSize];
  ASSERT_EQ(s.serialize(image, sizeof image), ParameterStore::kImageSize);
  const std::size_t body = ParameterStore::kImageSize - 4;
  const std::uint32_t stored = image[body] | (image[body + 1] << 8) | (image[body + 2] << 16) |
                               (static_cast<std::uint32_t>(image[body + 3]) << 24);
  EXPECT_EQ(stored, crc32(image, body));
  ParameterStore t;
  EXPECT_EQ(t.deserialize(image, sizeof image), StorageResult::Ok);
  image[0] ^= 0xFF;
  EXPECT_EQ(t.deserialize(image, sizeof image), StorageResult::BadMagic);
}

TEST_F(NodeTest, CurrentOffsetCalibrationAveragesAndStores) {
  drain();
  hw.sample.current = {0.05f, -0.02f, 0.0f};
  send(CalibrationCommand{kNode, CalibrationProcedure::CurrentOffset, 0b011, 0.0f});
  EXPECT_EQ(node.calibration_status(), CalibrationStatus::Running);
  std::vector<CalibrationProgress> progress;
  for (int i = 0; i < 250 && node.calibration_status() == CalibrationStatus::Running; ++i) {
    step();
    for (auto& p : sent<CalibrationProgress>(drain())) progress.push_back(p);
  }
  EXPECT_EQ(node.calibration_status(), CalibrationStatus::Done);
  EXPECT_NEAR(node.parameters().f32(param::kCurrentOffset + 0), 0.05f, 1e-6);
  EXPECT_NEAR(node.parameters().f32(param::kCurrentOffset + 1), -0.02f, 1e-6);
  EXPECT_EQ(node.parameters().f32(param::kCurrentOffset + 2), 0.0f);  // not selected
  ASSERT_GE(progress.size(), 2u);
  EXPECT_EQ(progress.front().status, CalibrationStatus::Running);
  EXPECT_EQ(progress.back().status, CalibrationStatus::Done);
  EXPECT_EQ(progress.back().percent, 100);
}

TEST_F(NodeTest, FindIndexDrivesUntilIndexAndZeroesThere) {
  drain();
  send(CalibrationCommand{kNode, CalibrationProcedure::FindIndex, 0b001, 0.4f});
  step();
  EXPECT_FLOAT_EQ(hw.applied[0], 0.4f);  // creeping with the bounded current
  hw.sample.position = {0.3f, 0, 0};
  hw.sample.index_seen[0] = true;
  step();
  EXPECT_EQ(node.calibration_status(), CalibrationStatus::Done);
  EXPECT_FLOAT_EQ(node.parameters().f32(param::kPositionOffset), -0.3f);
  EXPECT_EQ(hw.applied, (JointArray{0, 0, 0}));
}

TEST_F(NodeTest, CalibrationRefusedWhenOperational) {
  bring_up();
  send(CalibrationCommand{kNode, CalibrationProcedure::CurrentOffset, 1, 0.0f});
  auto progress = sent<CalibrationProgress>(drain());
  ASSERT_EQ(progress.size(), 1u);
  EXPECT_EQ(progress[0].status, CalibrationStatus::Failed);
}

TEST_F(NodeTest, PeriodicHeartbeatAndAuxFrames) {
  drain();
  for (int i = 0; i < 100; ++i) step();  // 100 ms
  auto ms = drain();
  EXPECT_EQ(sent<Heartbeat>(ms).size(), 1u);   // 100 ms period
  EXPECT_EQ(sent<AuxState>(ms).size(), 10u);   // 10 ms period
  EXPECT_EQ(sent<CurrentState>(ms).size(), 10u);
}

}  // namespace
}  // namespace vesica::fp
