// The guided hand steps (issue 32): roll sensor offset, jaw handle span and pedal travel. A
// scripted hand in the emulator moves as each prompt says, waits, and accepts; the readings are
// the random arm's ground truth over 20 seeds. A retry starts a step's prompts again; a pedal
// that barely moves is refused; a node that negotiated 1.1 is refused before anything is asked.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "calibration_rig.h"
#include "device/calibration/arm_calibrator.h"
#include "device/calibration/calibration_abort.h"
#include "device/calibration/calibration_step.h"

namespace vesica::device::calibration {
namespace {

using testing::CalibrationRig;
namespace emu = fp::emulator;
constexpr double kRollCount = 2.0 * std::numbers::pi / 16384.0;

// Moves what each prompt names, over 0.4 s of plant time; 0.3 s later accepts (or retries).
struct ScriptedHand {
  explicit ScriptedHand(CalibrationRig& r) : rig(r) {}
  CalibrationRig& rig;
  double pedal_stroke = 1.0;  ///< how far "pressed to its stop" gets (0.05: a pedal with no travel)
  int retries = 0;            ///< the person asks for this many retries of each step, at its last prompt
  std::string last_key;
  double started = 0.0;
  emu::HandTarget target;
  int prompts = 0;

  HandReply operator()(const HandPromptSpec& p, double) {
    const std::string key = p.step + "/" + std::to_string(p.prompt_index) + "/" + std::to_string(p.attempt);
    emu::ArmPlant& plant = rig.emulator->plant();
    if (key != last_key) {
      last_key = key;
      ++prompts;
      started = plant.time_s();
      emu::HandTarget next = target;
      next.p_T = emu::TipPosition(plant.q());            // the other hand keeps the instrument where it is
      if (p.step == "roll offset") next.roll_rad = 0.0;  // the mark at the top: true roll zero
      if (p.step == "jaw span") next.jaw_rad = p.prompt_index == 0 ? 0.0 : 0.7;  // squeezed past its stop
      if (p.step == "pedal travel") next.pedal_travel = p.prompt_index == 0 ? 0.0 : pedal_stroke;
      emu::HandScript script;
      script.Add(started, target);
      script.Add(started + 0.4, next);
      plant.SetHandScript(script);
      target = next;
    }
    if (plant.time_s() < started + 0.7) return HandReply::kWait;
    if (p.attempt <= retries && p.prompt_index == p.prompt_count - 1) return HandReply::kRetry;
    return HandReply::kAccept;
  }
};

CalibrationResult RunHandSteps(CalibrationRig& rig, ScriptedHand& hand) {
  // Before: the instrument turned away from its mark, handle half open, foot resting off the pedal.
  hand.target.holding = true;
  hand.target.roll_rad = 1.0;
  hand.target.jaw_rad = 0.3;
  hand.target.pedal_travel = 0.0;
  hand.target.p_T = emu::TipPosition(rig.emulator->plant().q());
  rig.emulator->plant().SetHandScript(emu::HandScript(hand.target));
  rig.RunUntil(rig.clock.now() + std::chrono::milliseconds(500));
  CalibrationPlan plan;
  plan.steps = kStepHandSensors;
  plan.hand_guide = std::ref(hand);
  return ArmCalibrator(*rig.link, plan).Run();
}

class HandSensorSteps : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(HandSensorSteps, TheScriptedHandsReadingsAreTheGroundTruth) {
  CalibrationRig rig(GetParam());
  ScriptedHand hand(rig);
  const CalibrationResult r = RunHandSteps(rig, hand);
  ASSERT_EQ(r.abort, AbortReason::kNone) << r.failed_step << ": " << r.message;
  EXPECT_EQ(hand.prompts, 5);  // roll; jaw closed, open; pedal released, pressed
  const emu::ArmGroundTruth& t = rig.truth;
  const HandSensorCalibration& h = r.hand;
  ASSERT_TRUE(h.roll_measured && h.jaw_measured && h.pedal_measured);
  // Roll: the reading at true zero is the offset, within 3 counts (the fingers' spring against
  // the roll bearing's friction leaves at most 2).
  EXPECT_LE(std::abs(std::remainder(h.roll_offset_rad - t.roll_offset(), 2.0 * std::numbers::pi)), 3 * kRollCount)
      << h.roll_offset_rad << " vs " << t.roll_offset();
  // ADCs: exactly what the converters give at the handle's and the pedal's ends.
  EXPECT_EQ(h.jaw_closed_raw, t.jaw_closed_raw());
  EXPECT_EQ(h.jaw_open_raw, t.jaw_open_raw());
  EXPECT_EQ(h.pedal_up_raw, t.pedal_up_raw());
  EXPECT_EQ(h.pedal_down_raw, t.pedal_down_raw());
  EXPECT_EQ(h.jaw_attempts, 1);
  EXPECT_EQ(h.pedal_attempts, 1);
}

INSTANTIATE_TEST_SUITE_P(TwentySeededArms, HandSensorSteps, ::testing::Range<std::uint64_t>(1, 21));

TEST(HandSensorStepsTest, ARetryStartsTheStepsPromptsAgain) {
  CalibrationRig rig(4);
  ScriptedHand hand(rig);
  hand.retries = 1;
  const CalibrationResult r = RunHandSteps(rig, hand);
  ASSERT_EQ(r.abort, AbortReason::kNone) << r.message;
  EXPECT_EQ(hand.prompts, 10);  // every prompt twice
  EXPECT_EQ(r.hand.roll_attempts, 2);
  EXPECT_EQ(r.hand.jaw_attempts, 2);
  EXPECT_EQ(r.hand.pedal_attempts, 2);
  EXPECT_EQ(r.hand.jaw_open_raw, rig.truth.jaw_open_raw());
  EXPECT_EQ(r.hand.pedal_down_raw, rig.truth.pedal_down_raw());
}

TEST(HandSensorStepsTest, APedalWithNoTravelIsRefused) {
  CalibrationRig rig(9);
  ScriptedHand hand(rig);
  hand.pedal_stroke = 0.05;  // the pedal hardly moves: about 150 counts
  const CalibrationResult r = RunHandSteps(rig, hand);
  EXPECT_EQ(r.abort, AbortReason::kMeasurement);
  EXPECT_EQ(r.failed_step, "hand sensors");
  EXPECT_NE(r.message.find("pedal travel: the pedal has no travel: "), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("counts between released and pressed (at least 500) (refused after 3 tries)"),
            std::string::npos)
      << r.message;
  EXPECT_FALSE(r.saved);
  EXPECT_EQ(hand.prompts, 1 + 2 + 3 * 2);                         // roll, jaw, then the pedal's two prompts three times
  rig.RunUntil(rig.clock.now() + std::chrono::milliseconds(10));  // the abort frame arrives
  EXPECT_FALSE(rig.emulator->node().calibration_session_open());
}

TEST(HandSensorStepsTest, WithoutAPersonTheStepStopsAndSaysWhy) {
  CalibrationRig rig(2);
  CalibrationPlan plan;
  plan.steps = kStepHandSensors;
  const CalibrationResult r = ArmCalibrator(*rig.link, plan).Run();
  EXPECT_EQ(r.abort, AbortReason::kMeasurement);
  EXPECT_NE(r.message.find("roll offset: needs a person to move the hand at an interactive tool"), std::string::npos)
      << r.message;
}

TEST(HandSensorStepsTest, ANodeThatNegotiatedProtocol1Point1IsRefusedBeforeAnyPrompt) {
  CalibrationRig rig(3);
  rig.link->Connect();
  // The host speaks 1.1 to it: the node negotiates 1.1 and says so in its Identity.
  fp::CanFrame f;
  ASSERT_EQ(fp::encode(fp::Hello{1, fp::kProtocolMajor, 1}, f), fp::EncodeError::None);
  rig.tool_ep.send(f, rig.clock.now() + std::chrono::milliseconds(1));
  rig.link->AwaitHeartbeat();
  ASSERT_EQ(rig.link->negotiated_minor(), 1);
  rig.link->BeginSession(0b111, 0.6);
  ScriptedHand hand(rig);
  CalibrationPlan plan;
  plan.hand_guide = std::ref(hand);
  CalibrationResult result;
  JointServo servo{ArmDesign{}};
  StepContext ctx{*rig.link, servo, plan, result};
  try {
    CalibrateJawSpan(ctx);
    FAIL() << "the step ran";
  } catch (const CalibrationAbort& e) {
    EXPECT_EQ(e.reason(), AbortReason::kProtocolTooOld);
    EXPECT_NE(std::string(e.what()).find("node 1 speaks protocol 1.1 with this tool; the guided hand steps need 1.2 "
                                         "(update the arm's firmware); nothing was changed"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(hand.prompts, 0);
  rig.link->AbortSession();
}

}  // namespace
}  // namespace vesica::device::calibration
