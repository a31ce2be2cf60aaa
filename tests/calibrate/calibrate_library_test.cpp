// The commands as a library (what the trainer's panel will call): progress comes step by step
// through ToolUi, and the panel's abort flag set mid-step ends the calibration with the arm
// disabled, no current, its stored calibration in force and its flash untouched.
#include <gtest/gtest.h>

#include <atomic>
#include <map>

#include "app/calibrate/commands.h"
#include "app/calibrate/exit_codes.h"
#include "device/calibration/calibration_abort.h"
#include "firmware_protocol/emulator/arm_ground_truth.h"
#include "firmware_protocol/node/parameter_table.h"
#include "tool_process.h"

namespace vesica::app::calibrate {
namespace {

// A panel: records the steps it was shown and presses Abort when `abort_at` begins.
class PanelUi final : public ToolUi {
 public:
  std::atomic<bool> abort{false};
  std::string abort_at;
  std::vector<std::string> steps;
  std::map<std::string, double> last_fraction;
  int prompts = 0;
  void Progress(int, const std::string& step, double fraction, double) override {
    if (steps.empty() || steps.back() != step) steps.push_back(step);
    last_fraction[step] = fraction;
    if (step == abort_at) abort = true;
  }
  bool ConfirmMotion(const MotionNotice& notice) override {
    ++prompts;
    EXPECT_EQ(notice.arm, 1);
    EXPECT_EQ(notice.motions.size(), 5u);
    return true;
  }
  void Note(const std::string&) override {}
};

ToolOptions EmulatedOptions(const std::string& dir) {
  ToolOptions o;
  o.bus.kind = BusSpec::Kind::kEmulated;
  o.bus.emulated_seed = 33;
  o.data_dir = dir;
  o.command = "calibrate";
  o.date_s = 1790000000;
  return o;
}

TEST(CalibrateLibrary, ThePanelSeesEveryStepAndItsAbortLeavesTheStoredCalibration) {
  const std::string dir = testing::FreshDir("library");
  {
    PanelUi ui;
    ToolSession session(EmulatedOptions(dir), ui, &ui.abort);
    const CommandOutcome o = Calibrate(session, 1, CalibrateRequest{});
    ASSERT_EQ(o.exit_code, kExitOk) << o.text;
    EXPECT_EQ(ui.prompts, 1);
    EXPECT_EQ(ui.steps, (std::vector<std::string>{"current offset", "encoder direction", "range", "index", "friction",
                                                  "gravity", "save"}));
    for (const auto& [step, fraction] : ui.last_fraction) EXPECT_EQ(fraction, 1.0) << step;
  }
  PanelUi ui;
  ui.abort_at = "friction";
  ToolSession session(EmulatedOptions(dir), ui, &ui.abort);
  // The arm as stored, before the second calibration opens its session.
  const CommandOutcome info = Info(session, 1);
  ASSERT_EQ(info.exit_code, kExitOk);
  auto* arm = session.bus().emulated_arm(1);
  ASSERT_NE(arm, nullptr);
  const std::vector<std::uint8_t> flash = arm->board().flash().bytes();
  const float coulomb = arm->node().parameters().f32(fp::param::kCoulombFriction + 1);

  const CommandOutcome o = Calibrate(session, 1, CalibrateRequest{});
  EXPECT_EQ(o.exit_code, kExitAborted);
  EXPECT_EQ(o.json["error"]["step"], "friction");
  EXPECT_EQ(o.json["error"]["reason"], "abort_requested");
  EXPECT_EQ(o.json["error"]["message"], "arm 1: calibration aborted by the user; the stored calibration is in force");
  // Let the node take the abort frame.
  // A few bus periods for the node to take the abort frame (the link still refuses to go on).
  std::string error;
  device::calibration::CalibrationLink* link = session.LinkTo(1, &error);
  for (int i = 0; i < 20; ++i) {
    try {
      link->Cycle({});
    } catch (const device::calibration::CalibrationAbort&) {
    }
  }
  EXPECT_FALSE(arm->node().enabled());
  EXPECT_FALSE(arm->node().calibration_session_open());
  for (float a : arm->node().applied_current()) EXPECT_EQ(a, 0.0f);
  EXPECT_EQ(arm->node().active_slot(), 0);
  EXPECT_EQ(arm->node().parameters().f32(fp::param::kCoulombFriction + 1), coulomb);
  EXPECT_EQ(arm->board().flash().bytes(), flash) << "something was written";
}

// A panel with a person at the arm: for each hand prompt it moves the emulated arm's jaw handle
// or pedal as asked, shows the live value for a while, then accepts; the first jaw attempt it
// retries. A panel that does not implement GuideHand (ToolUi's default) declines.
class HandPanelUi final : public ToolUi {
 public:
  explicit HandPanelUi(ToolSession** session) : session_(session) {}
  void Progress(int, const std::string&, double, double) override {}
  bool ConfirmMotion(const MotionNotice&) override { return true; }
  void Note(const std::string&) override {}
  HandAnswer GuideHand(const HandPrompt& p, double live) override {
    EXPECT_EQ(p.arm, 1);
    EXPECT_EQ(p.unit, "counts");
    const std::string key = p.step + std::to_string(p.prompt_index) + "/" + std::to_string(p.attempt);
    fp::emulator::ArmPlant& plant = (*session_)->bus().emulated_arm(1)->plant();
    if (key != key_) {
      key_ = key;
      calls_ = 0;
      prompts.push_back(p.step + " " + std::to_string(p.prompt_index + 1) + "/" + std::to_string(p.prompt_count) +
                        " try " + std::to_string(p.attempt));
      fp::emulator::HandTarget t;
      t.holding = false;
      t.jaw_rad = p.step == "jaw span" && p.prompt_index == 1 ? 0.7 : 0.0;
      t.pedal_travel = p.step == "pedal travel" && p.prompt_index == 1 ? 1.0 : 0.0;
      plant.SetHandScript(fp::emulator::HandScript(t));
    }
    last_live = live;
    if (++calls_ < 10) return HandAnswer::kWait;  // 10 calls, 20 ms of bus time apart
    if (p.step == "jaw span" && p.attempt == 1 && p.prompt_index == 1) return HandAnswer::kRetry;
    return HandAnswer::kAccept;
  }
  std::vector<std::string> prompts;
  double last_live = -1.0;

 private:
  ToolSession** session_;
  std::string key_;
  int calls_ = 0;
};

class NoHandUi final : public ToolUi {
 public:
  void Progress(int, const std::string&, double, double) override {}
  bool ConfirmMotion(const MotionNotice&) override { return true; }
  void Note(const std::string&) override {}
};

TEST(CalibrateLibrary, TheGuidedHandStepsPromptWithALiveValueAndRetry) {
  const std::string dir = testing::FreshDir("library-hand");
  {
    NoHandUi ui;
    ToolSession session(EmulatedOptions(dir), ui, nullptr);
    ASSERT_EQ(Calibrate(session, 1, CalibrateRequest{}).exit_code, kExitOk);  // a calibrated arm to start from
  }
  ToolSession* current = nullptr;
  HandPanelUi ui(&current);
  ToolSession session(EmulatedOptions(dir), ui, nullptr);
  current = &session;
  CalibrateRequest request;
  request.steps = {Step::kJawSpan, Step::kPedalTravel};
  const CommandOutcome o = Calibrate(session, 1, request);
  ASSERT_EQ(o.exit_code, kExitOk) << o.text;
  EXPECT_EQ(ui.prompts,
            (std::vector<std::string>{"jaw span 1/2 try 1", "jaw span 2/2 try 1", "jaw span 1/2 try 2",
                                      "jaw span 2/2 try 2", "pedal travel 1/2 try 1", "pedal travel 2/2 try 1"}));
  const fp::emulator::ArmGroundTruth t = fp::emulator::RandomArm(33);
  const nlohmann::json& hand = o.json["measured"]["hand"];
  EXPECT_EQ(hand["jaw"]["closed_raw"], t.jaw_closed_raw());
  EXPECT_EQ(hand["jaw"]["open_raw"], t.jaw_open_raw());
  EXPECT_EQ(hand["jaw"]["attempts"], 2);
  EXPECT_EQ(hand["pedal"]["released_raw"], t.pedal_up_raw());
  EXPECT_EQ(hand["pedal"]["pressed_raw"], t.pedal_down_raw());
  EXPECT_EQ(ui.last_live, t.pedal_down_raw());  // the live value was the sensor's
  EXPECT_TRUE(o.json["saved"].get<bool>());     // reported and (protocol 1.3) stored

  // A panel without GuideHand declines: the step stops, saying why.
  NoHandUi plain;
  ToolSession again(EmulatedOptions(dir), plain, nullptr);
  request.steps = {Step::kRollOffset};
  const CommandOutcome declined = Calibrate(again, 1, request);
  EXPECT_EQ(declined.exit_code, kExitAborted) << declined.text;
  EXPECT_NE(declined.text.find("roll offset: stopped at the prompt"), std::string::npos) << declined.text;
}

}  // namespace
}  // namespace vesica::app::calibrate
