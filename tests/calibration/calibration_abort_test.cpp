// A calibration stopped at a random moment of each step (50 seeds): the bus to the arm is cut,
// the E-stop opens, or the technician aborts. Each time the arm ends disabled, its stored
// calibration is in force again (the node's parameters are the stored ones, nothing was
// written), and the tool says what happened. Also: an older node and a missing one are refused
// before anything moves or is written.
#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "calibration_rig.h"
#include "device/calibration/arm_calibrator.h"
#include "firmware_protocol/node/parameter_table.h"

namespace vesica::device::calibration {
namespace {

using testing::CalibrationRig;
using namespace std::chrono_literals;

// The persistent calibration values a node runs on.
std::vector<std::uint32_t> CalibrationValues(const fp::ParameterStore& p) {
  std::vector<std::uint32_t> out;
  for (const fp::ParameterSpec& s : fp::kParameterSpecs)
    if (s.persistent && s.access == fp::ParameterAccess::ReadWrite) out.push_back(p.u32(s.index));
  return out;
}

enum class Event { kBusLoss, kEStop, kAbortRequest };

TEST(CalibrationAbortTest, InterruptedAtARandomMomentOfEachStepLeavesTheStoredCalibration) {
  const std::vector<std::string> steps = {"current offset", "encoder direction", "range", "index",
                                          "friction",       "gravity",           "save"};
  // Rough lengths of the steps (s of bus time) to draw a moment inside each.
  const std::map<std::string, double> length = {{"current offset", 0.03}, {"encoder direction", 1.5}, {"range", 12.0},
                                                {"index", 3.0},           {"friction", 18.0},         {"gravity", 5.0},
                                                {"save", 0.012}};
  std::set<std::string> interrupted_steps;
  std::map<AbortReason, int> reasons;
  for (std::uint64_t seed = 1; seed <= 50; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    CalibrationRig rig(seed);
    // A previous calibration, stored before this one starts.
    {
      CalibrationLink& l = *rig.link;
      l.Connect();
      l.WriteF32(fp::param::kPositionOffset + 0, 0.0123f);
      l.WriteF32(fp::param::kCoulombFriction + 1, 0.007f);
      l.WriteI32(fp::param::kEncoderDirection + 2, -1);
      l.WriteU32(fp::param::kCalibrationDate_s, 1'700'000'000u);
      l.Save();
    }
    const auto& node = rig.emulator->node();
    const std::vector<std::uint32_t> stored = CalibrationValues(node.parameters());
    const std::vector<std::uint8_t> flash = rig.emulator->board().flash().bytes();
    const int active = node.active_slot();
    ASSERT_NE(active, -1);

    std::mt19937_64 rng(seed);
    const std::string target = steps[(seed - 1) % steps.size()];
    const auto event = static_cast<Event>((seed - 1) / steps.size() % 3);
    const double fraction = std::uniform_real_distribution<double>(0.0, 0.9)(rng);
    double inject_at = -1.0;
    bool injected = false;
    std::string step_at_injection;
    std::string current_step;
    CalibrationPlan plan;
    plan.progress = [&](const std::string& step, double f) {
      current_step = step;
      if (step == target && f == 0.0 && inject_at < 0) inject_at = rig.link->now_s() + fraction * length.at(step);
    };
    rig.each_step = [&] {
      if (injected || inject_at < 0 || rig.link->now_s() < inject_at) return;
      injected = true;
      step_at_injection = current_step;
      switch (event) {
        case Event::kBusLoss:
          rig.arm_ep.set_connected(false);
          break;
        case Event::kEStop:
          rig.emulator->board().set_estop_input(true);
          break;
        case Event::kAbortRequest:
          rig.link->RequestAbort();
          break;
      }
    };
    ArmCalibrator calibrator(*rig.link, plan);
    const CalibrationResult r = calibrator.Run();
    ASSERT_TRUE(injected) << "target step " << target;
    interrupted_steps.insert(step_at_injection);
    const AbortReason expected = event == Event::kBusLoss ? AbortReason::kLinkLost
                                 : event == Event::kEStop ? AbortReason::kEmergencyStop
                                                          : AbortReason::kAbortRequested;
    EXPECT_EQ(r.abort, expected) << r.failed_step << ": " << r.message;
    ++reasons[r.abort];
    EXPECT_FALSE(r.saved);
    EXPECT_FALSE(r.message.empty());
    EXPECT_NE(r.message.find(expected == AbortReason::kLinkLost        ? "link lost"
                             : expected == AbortReason::kEmergencyStop ? "emergency stop"
                                                                       : "aborted"),
              std::string::npos)
        << r.message;
    // The node has had time to notice (its 250 ms session watchdog, the abort frame).
    rig.RunUntil(rig.clock.now() + 300ms);
    EXPECT_FALSE(node.enabled());
    EXPECT_FALSE(node.calibration_session_open());
    EXPECT_EQ(rig.emulator->board().applied_currents(), (fp::JointArray{0, 0, 0}));
    EXPECT_EQ(CalibrationValues(node.parameters()), stored) << "the stored calibration is not in force";
    EXPECT_EQ(node.active_slot(), active);
    EXPECT_EQ(rig.emulator->board().flash().bytes(), flash) << "something was written";
  }
  EXPECT_EQ(interrupted_steps.size(), steps.size());  // every step was interrupted at least once
  EXPECT_EQ(
      reasons[AbortReason::kLinkLost] + reasons[AbortReason::kEmergencyStop] + reasons[AbortReason::kAbortRequested],
      50);
}

// A node with firmware from before the calibration session (protocol 1.0) on the bus.
struct OldNode {
  fp::VirtualBusEndpoint& ep;
  bool asked_anything_else = false;
  void Serve() {
    fp::TimedFrame rx;
    while (ep.receive(rx)) {
      fp::Message m;
      if (fp::decode(rx.frame, m) != fp::DecodeError::None) continue;
      if (std::holds_alternative<fp::Hello>(m)) {
        fp::CanFrame f;
        fp::encode(fp::Identity{1, 1, 0, 0, 0, 0x01D}, f);
        ep.send(f, ep.now() + 1ms);
      } else if (std::holds_alternative<fp::ParameterRequest>(m) || std::holds_alternative<fp::CalibrationCommand>(m) ||
                 std::holds_alternative<fp::CurrentCommand>(m)) {
        asked_anything_else = true;
      }
    }
  }
};

TEST(CalibrationAbortTest, ANodeSpeakingProtocol1Point0IsRefusedBeforeAnythingIsSent) {
  fp::VirtualClock clock;
  fp::VirtualBus bus{clock};
  fp::VirtualBusEndpoint& tool = bus.attach("tool");
  OldNode old{bus.attach("old node")};
  CalibrationLink link(tool, [&](fp::Nanoseconds t) {
    while (clock.now() < t) {
      bus.advance(100us);
      old.Serve();
    }
  });
  ArmCalibrator calibrator(link, CalibrationPlan{});
  const CalibrationResult r = calibrator.Run();
  EXPECT_EQ(r.abort, AbortReason::kProtocolTooOld);
  EXPECT_EQ(r.failed_step, "connect");
  EXPECT_NE(r.message.find("speaks protocol 1.0; calibration needs 1.1"), std::string::npos) << r.message;
  EXPECT_FALSE(old.asked_anything_else);
}

TEST(CalibrationAbortTest, NoArmOnTheBusIsNoAnswer) {
  fp::VirtualClock clock;
  fp::VirtualBus bus{clock};
  fp::VirtualBusEndpoint& tool = bus.attach("tool");
  CalibrationLinkConfig config;
  config.node_id = 7;
  CalibrationLink link(
      tool, [&](fp::Nanoseconds t) { bus.run_until(t); }, config);
  const CalibrationResult r = ArmCalibrator(link, CalibrationPlan{}).Run();
  EXPECT_EQ(r.abort, AbortReason::kNoAnswer);
  EXPECT_NE(r.message.find("no answer from node 7"), std::string::npos) << r.message;
}

TEST(CalibrationAbortTest, ASecondCalibrationAfterAnAbortStartsFromAFaultFreeNode) {
  CalibrationRig rig(4);
  CalibrationPlan plan;
  bool stop = false;
  plan.progress = [&](const std::string& step, double) { stop = stop || step == "range"; };
  rig.each_step = [&] {
    if (stop) rig.emulator->board().set_estop_input(true);
  };
  EXPECT_EQ(ArmCalibrator(*rig.link, plan).Run().abort, AbortReason::kEmergencyStop);
  EXPECT_EQ(rig.emulator->node().latched_fault(), fp::FaultCode::EmergencyStop);
  // E-stop released: the next run clears the fault and calibrates.
  rig.each_step = nullptr;
  rig.emulator->board().set_estop_input(false);
  plan.progress = nullptr;
  const CalibrationResult r = ArmCalibrator(*rig.link, plan).Run();
  EXPECT_EQ(r.abort, AbortReason::kNone) << r.failed_step << ": " << r.message;
  EXPECT_TRUE(r.saved);
  EXPECT_EQ(rig.emulator->node().latched_fault(), fp::FaultCode::None);
}

}  // namespace
}  // namespace vesica::device::calibration
