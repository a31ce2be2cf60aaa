// Homing after power-up (protocol 1.4). A random arm, calibrated where it powered up, is switched
// off, moved 0.7 rad (70 mm) by hand and switched on again: its incremental encoders count from
// there, so the stored offsets read every joint 0.7 rad off. The node says it is not homed and
// refuses Enable; HomeArm (lower hard stop, then the reference index) finds the frame again to
// within an encoder count, without writing the flash. Stopped midway (abort, E-stop) the arm is
// left disabled and not homed; a node of protocol 1.3 cannot be homed and nothing moves.
#include "device/calibration/homing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "firmware_protocol/emulator/arm_emulator.h"
#include "firmware_protocol/emulator/arm_ground_truth.h"
#include "firmware_protocol/node/parameter_table.h"
#include "firmware_protocol/transport/virtual_bus.h"

namespace vesica::device::calibration {
namespace {

using namespace std::chrono_literals;
namespace emu = fp::emulator;

constexpr double kMoved = 0.7;  // rad (insertion: 0.07 m), how far the arm was moved while off

// A seeded random arm whose flash holds the calibration of where it powered up (ground truth, as
// a whole calibration finds it, the soft range 0.02 rad / 2 mm inside the stops), on a virtual
// bus with the tool's link; the node requires homing.
struct HomingRig {
  emu::ArmGroundTruth truth;
  fp::VirtualClock clock;
  fp::VirtualBus bus{clock};
  fp::VirtualBusEndpoint& tool_ep = bus.attach("tool");
  fp::VirtualBusEndpoint& arm_ep = bus.attach("arm");
  std::unique_ptr<emu::ArmEmulator> emulator;
  std::unique_ptr<CalibrationLink> link;
  std::function<void()> each_step;
  emu::Joint4 moved{};

  explicit HomingRig(std::uint64_t seed, std::uint8_t firmware_minor = fp::kProtocolMinor)
      : truth(emu::RandomArm(seed)) {
    truth.plant.factory_calibrated = true;
    emu::ArmEmulator::Config ec;
    ec.board.park_position = {0.0f, 0.0f, 0.135f};
    ec.require_homing = true;
    ec.firmware_minor = firmware_minor;
    emulator = std::make_unique<emu::ArmEmulator>(arm_ep, truth.plant, truth.power_up, ec);
    emu::HandTarget let_go;
    let_go.holding = false;
    emulator->plant().SetHandScript(emu::HandScript(let_go));
    link = std::make_unique<CalibrationLink>(tool_ep, [this](fp::Nanoseconds t) { RunUntil(t); });
    // The calibration's range, stored with the factory's values (a whole calibration writes it).
    auto& node = emulator->node();
    for (int j = 0; j < 3; ++j) {
      const double margin = j < 2 ? 0.02 : 0.002;
      Write(fp::param::kJointMin + j, static_cast<float>(truth.lower_stop(j) + margin));
      Write(fp::param::kJointMax + j, static_cast<float>(truth.upper_stop(j) - margin));
    }
    Write(fp::param::kCalibrationToolVersion, 0x000104u);
    fp::CanFrame f;
    fp::encode(fp::ParameterRequest{node.node_id(), fp::ParameterOp::Save, fp::ParameterType::None, 0, 0}, f);
    node.on_frame(f, 0);
    while (node.pop_tx(f)) {
    }
    // Off, moved by hand, on.
    moved = emu::MovedWhileOff(truth.plant, truth.power_up, kMoved, seed);
    emulator->PowerCycleAt(moved);
  }
  void Write(std::uint16_t index, float v) {
    fp::CanFrame f;
    fp::encode(fp::ParameterRequest{emulator->node().node_id(), fp::ParameterOp::Write, fp::ParameterType::F32, index,
                                    fp::f32_bits(v)},
               f);
    emulator->node().on_frame(f, 0);
  }
  void Write(std::uint16_t index, std::uint32_t v) {
    fp::CanFrame f;
    fp::encode(
        fp::ParameterRequest{emulator->node().node_id(), fp::ParameterOp::Write, fp::ParameterType::U32, index, v}, f);
    emulator->node().on_frame(f, 0);
  }
  void RunUntil(fp::Nanoseconds t) {
    while (clock.now() < t) {
      bus.advance(100us);
      emulator->RunUntil(clock.now());
      if (each_step) each_step();
    }
  }
  /// What the node reads minus the truth, per joint, in encoder counts (a few SYNCs: fresh states).
  std::array<double, 3> ReadingErrorCounts() {
    for (int i = 0; i < 5; ++i) link->Cycle({});
    std::array<double, 3> e{};
    for (int j = 0; j < 3; ++j)
      e[j] = (link->sample().position[j] - emulator->plant().q()[emu::JointOfMotor(j)]) / truth.count(j);
    return e;
  }
};

TEST(HomingTest, PoweredUpMovedReadsWrongUntilHomedThenRightToACount) {
  for (std::uint64_t seed : {1u, 2u, 3u, 4u, 5u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    HomingRig rig(seed);
    const std::vector<std::uint8_t> flash = rig.emulator->board().flash().bytes();
    rig.link->Connect();
    // Before homing: every joint reads off by the move (0.7 rad, 70 mm), and the node says so.
    const std::array<double, 3> before = rig.ReadingErrorCounts();
    for (int j = 0; j < 3; ++j) {
      const double off = before[j] * rig.truth.count(j);
      const double expected = -(rig.moved[emu::JointOfMotor(j)] - rig.truth.power_up[emu::JointOfMotor(j)]);
      EXPECT_NEAR(off, expected, 2 * rig.truth.count(j)) << "joint " << j;
      EXPECT_GT(std::abs(off), j < 2 ? 0.69 : 0.069) << "joint " << j;
    }
    rig.link->AwaitHeartbeat();
    EXPECT_TRUE(rig.link->node_not_homed());
    EXPECT_FALSE(rig.emulator->node().homed());

    const HomingResult r = HomeArm(*rig.link, HomingPlan{});
    ASSERT_TRUE(r.homed) << r.message;
    EXPECT_FALSE(r.was_homed);
    EXPECT_TRUE(rig.emulator->node().homed());
    // After: within an encoder count or so of the truth, on every joint: the offset itself (the
    // one that centres the reading on the truth), and the reading at rest.
    const std::array<double, 3> after = rig.ReadingErrorCounts();
    for (int j = 0; j < 3; ++j) {
      const int direction = rig.truth.plant.encoder[j].direction < 0 ? -1 : 1;
      const double park = j == 2 ? static_cast<double>(0.135f) : 0.0;
      const double true_offset = rig.moved[emu::JointOfMotor(j)] - direction * park + 0.5 * rig.truth.count(j);
      EXPECT_LE(std::abs(r.offset_after[j] - true_offset) / rig.truth.count(j), 1.0) << "joint " << j;
      EXPECT_LE(std::abs(after[j]), 1.5) << "joint " << j << " reads " << after[j] << " counts off";
      EXPECT_NEAR(r.correction[j], rig.moved[emu::JointOfMotor(j)] - rig.truth.power_up[emu::JointOfMotor(j)],
                  2 * rig.truth.count(j));
    }
    rig.link->AwaitHeartbeat();
    EXPECT_FALSE(rig.link->node_not_homed());
    // Nothing was written to the flash; the session ended, nothing enabled, no fault.
    EXPECT_EQ(rig.emulator->board().flash().bytes(), flash);
    EXPECT_FALSE(rig.emulator->node().calibration_session_open());
    EXPECT_FALSE(rig.emulator->node().enabled());
    EXPECT_EQ(rig.emulator->node().latched_fault(), fp::FaultCode::None);
    EXPECT_LT(r.bus_time_s, 20.0);
  }
}

// Start and enable as the bridge does: true when the node ends enabled.
bool TryEnable(HomingRig& rig) {
  rig.link->Cycle({});
  fp::CanFrame f;
  fp::encode(fp::Nmt{fp::NmtCommand::Start, rig.emulator->node().node_id()}, f);
  rig.tool_ep.send(f, rig.clock.now() + 1ms);
  rig.RunUntil(rig.clock.now() + 2ms);
  fp::encode(fp::Control{rig.emulator->node().node_id(), 0, fp::ControlCommand::Enable}, f);
  rig.tool_ep.send(f, rig.clock.now() + 1ms);
  rig.RunUntil(rig.clock.now() + 2ms);
  const bool enabled = rig.emulator->node().enabled();
  fp::encode(fp::Control{rig.emulator->node().node_id(), 1, fp::ControlCommand::Disable}, f);
  rig.tool_ep.send(f, rig.clock.now() + 1ms);
  fp::encode(fp::Nmt{fp::NmtCommand::EnterPreOperational, rig.emulator->node().node_id()}, f);
  rig.tool_ep.send(f, rig.clock.now() + 1ms);
  rig.RunUntil(rig.clock.now() + 2ms);
  return enabled;
}

TEST(HomingTest, EnableIsRefusedUntilHomed) {
  HomingRig rig(7);
  rig.link->Connect();
  EXPECT_FALSE(TryEnable(rig)) << "a node not homed must refuse Enable";
  EXPECT_EQ(rig.emulator->node().latched_fault(), fp::FaultCode::None);
  ASSERT_TRUE(HomeArm(*rig.link, HomingPlan{}).homed);
  EXPECT_TRUE(TryEnable(rig));
  // A power cycle loses it again.
  rig.emulator->PowerCycleAt(rig.moved);
  rig.link->Connect();
  EXPECT_FALSE(TryEnable(rig));
}

// The heartbeats a host that said Hello with `minor` receives for 300 ms: whether any said not homed.
bool HeartbeatSaysNotHomed(HomingRig& rig, std::uint8_t minor) {
  fp::CanFrame f;
  fp::encode(fp::Hello{rig.emulator->node().node_id(), fp::kProtocolMajor, minor}, f);
  rig.tool_ep.send(f, rig.clock.now() + 1ms);
  rig.RunUntil(rig.clock.now() + 300ms);
  bool flagged = false;
  int heartbeats = 0;
  fp::TimedFrame rx;
  while (rig.tool_ep.receive(rx)) {
    fp::Message m;
    if (fp::decode(rx.frame, m) != fp::DecodeError::None) continue;  // a 1.3 decoder would reject the bit
    if (const auto* hb = std::get_if<fp::Heartbeat>(&m)) {
      ++heartbeats;
      flagged = flagged || hb->not_homed;
    }
  }
  EXPECT_GE(heartbeats, 2);
  return flagged;
}

TEST(HomingTest, OnlyAHostOfProtocol14IsToldAndEnableIsRefusedEitherWay) {
  HomingRig rig(8);
  EXPECT_FALSE(HeartbeatSaysNotHomed(rig, 3)) << "a 1.3 host must not get a bit its decoder rejects";
  EXPECT_FALSE(TryEnable(rig)) << "positions unknown: refused for an older host too";
  EXPECT_TRUE(HeartbeatSaysNotHomed(rig, 4));
  // The bit is bit 4 of byte 1; the three above it stay reserved.
  fp::CanFrame f;
  ASSERT_EQ(fp::encode(fp::Heartbeat{1, fp::NodeState::PreOperational, false, fp::FaultCode::None, true}, f),
            fp::EncodeError::None);
  EXPECT_EQ(f.data[1] & 0x10, 0x10);
  fp::Message m;
  f.data[1] |= 0x20;
  EXPECT_EQ(fp::decode(f, m), fp::DecodeError::OutOfRange);
}

// Stopped at a moment of the homing: the arm ends disabled, not homed, with the stored offsets.
void ExpectLeftDisabledNotHomed(HomingRig& rig, const HomingResult& r, AbortReason reason) {
  EXPECT_FALSE(r.homed);
  EXPECT_EQ(r.abort, reason) << r.message;
  rig.RunUntil(rig.clock.now() + 50ms);
  const auto& node = rig.emulator->node();
  EXPECT_FALSE(node.homed());
  EXPECT_FALSE(node.enabled());
  EXPECT_FALSE(node.calibration_session_open());
  for (int j = 0; j < 3; ++j) {
    EXPECT_EQ(node.applied_current()[j], 0.0f);
    EXPECT_FLOAT_EQ(node.parameters().f32(fp::param::kPositionOffset + j), static_cast<float>(r.offset_before[j]));
  }
}

TEST(HomingTest, AbortMidHomeLeavesTheArmDisabledAndNotHomed) {
  // Into the stop search (1.5 s) and into the index creep (about 6 s).
  for (const double at_s : {1.5, 6.0}) {
    SCOPED_TRACE("abort at " + std::to_string(at_s) + " s");
    HomingRig rig(11);
    const double start = 1e-9 * static_cast<double>(rig.clock.now().count());
    rig.each_step = [&] {
      if (1e-9 * static_cast<double>(rig.clock.now().count()) - start > at_s) rig.link->RequestAbort();
    };
    const HomingResult r = HomeArm(*rig.link, HomingPlan{});
    ExpectLeftDisabledNotHomed(rig, r, AbortReason::kAbortRequested);
    EXPECT_NE(r.message.find("aborted"), std::string::npos) << r.message;
  }
}

TEST(HomingTest, EStopMidHomeLeavesTheArmDisabledAndNotHomed) {
  HomingRig rig(12);
  const double start = 1e-9 * static_cast<double>(rig.clock.now().count());
  rig.each_step = [&] {
    if (1e-9 * static_cast<double>(rig.clock.now().count()) - start > 3.0) rig.emulator->board().set_estop_input(true);
  };
  const HomingResult r = HomeArm(*rig.link, HomingPlan{});
  ExpectLeftDisabledNotHomed(rig, r, AbortReason::kEmergencyStop);
  EXPECT_EQ(rig.emulator->node().latched_fault(), fp::FaultCode::EmergencyStop);
}

TEST(HomingTest, ANodeOfProtocol13CannotBeHomedAndNothingMoves) {
  HomingRig rig(13, 3);
  rig.RunUntil(rig.clock.now() + 2s);  // powered up moving? settled, as nobody holds it
  const emu::Joint4 q = rig.emulator->plant().q();
  const HomingResult r = HomeArm(*rig.link, HomingPlan{});
  EXPECT_FALSE(r.homed);
  EXPECT_EQ(r.abort, AbortReason::kProtocolTooOld);
  EXPECT_NE(r.message.find("speaks protocol 1.3; homing needs 1.4 (update the arm's firmware)"), std::string::npos)
      << r.message;
  rig.RunUntil(rig.clock.now() + 100ms);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(rig.emulator->plant().q()[k], q[k], 1e-6);
  // It has no homing: it never says it is not homed, and enables as before.
  EXPECT_FALSE(rig.emulator->node().homing_required());
  EXPECT_TRUE(rig.emulator->node().homed());
}

}  // namespace
}  // namespace vesica::device::calibration
