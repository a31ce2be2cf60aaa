// A session's metrics stay storable whatever its input: an insertion far beyond any instrument
// (a corrupt recording said 1e308 m) is clamped, so the tip path length stays finite and the
// record passes the store's validation instead of being lost at the end of the session.

#include "app/session/dissection_session.h"

#include <gtest/gtest.h>

#include "app/records/session_store.h"
#include "app/render/scene_meshes.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_setup.h"
#include "device/input/input_recording.h"

namespace vesica::app {
namespace {

TEST(DissectionSessionTest, HugeInsertionIsClampedAndTheMetricsStayStorable) {
  const Scenario scenario = LoadScenario(DefaultScenarioPath());
  const auto model = BuildDissectionModelFor(scenario, LoadSceneMeshes(scenario));
  DissectionSession session(model, DefaultCauteryParams());
  device::InputFrame frame;
  frame.instruments[0].pose.insertion_m = 0.05;
  frame.instruments[1].pose.insertion_m = 0.05;
  session.Step(frame);
  frame.instruments[0].pose.insertion_m = 1e308;  // the recorded fault
  session.Step(frame);
  EXPECT_EQ(session.clamped_inputs(), 1);
  frame.instruments[0].pose.insertion_m = 0.05;
  session.Step(frame);

  const SessionMetrics m = session.metrics();
  // Out to the clamp and back: twice (0.5 - 0.05) m along the shaft.
  EXPECT_NEAR(m.path_length_left_m, 2 * (DissectionSession::kMaxInsertion_m - 0.05), 1e-9);
  EXPECT_EQ(m.path_length_right_m, 0.0);
  SessionRecord record;
  record.trainee_id = "resident";
  record.metrics = m;
  EXPECT_NO_THROW(ValidateRecord(record));
}

TEST(DissectionSessionTest, NegativeOrNonFiniteInsertionIsStillRefused) {
  const Scenario scenario = LoadScenario(DefaultScenarioPath());
  const auto model = BuildDissectionModelFor(scenario, LoadSceneMeshes(scenario));
  DissectionSession session(model, DefaultCauteryParams());
  device::InputFrame frame;
  frame.instruments[1].pose.insertion_m = -0.01;
  EXPECT_THROW(session.Step(frame), std::invalid_argument);
  frame.instruments[1].pose.insertion_m = std::numeric_limits<double>::infinity();
  EXPECT_THROW(session.Step(frame), std::invalid_argument);
  EXPECT_EQ(session.metrics().duration_s, 0.0);
}

// The committed dissection burns with the hook; the same hands with the scissors (or the clip
// applier) in the right port press the same pedal and burn nothing.
TEST(DissectionSessionTest, OnlyTheHookBurnsWhenThePedalIsPressed) {
  const Scenario scenario = LoadScenario(DefaultScenarioPath());
  const auto model = BuildDissectionModelFor(scenario, LoadSceneMeshes(scenario));
  const device::InputRecording rec = device::ReadInputRecording(DefaultScenarioPath().parent_path().parent_path() /
                                                                "recordings" / "dissection.csv");
  DissectionSession hook(model, DefaultCauteryParams());
  std::size_t frames = 0;
  for (; frames < rec.frames.size() && hook.metrics().springs_cut == 0; ++frames) hook.Step(rec.frames[frames]);
  ASSERT_GT(hook.metrics().springs_cut, 0) << "the committed dissection cuts a spring";
  ASSERT_GT(hook.metrics().cautery_on_s, 0.0);
  for (physics::InstrumentTool tool : {physics::InstrumentTool::kScissors, physics::InstrumentTool::kClipApplier}) {
    DissectionSession other(model, DefaultCauteryParams());
    for (std::size_t i = 0; i < frames; ++i) {
      device::InputFrame f = rec.frames[i];
      f.right_tool = tool;
      other.Step(f);
    }
    const SessionMetrics m = other.metrics();
    EXPECT_EQ(m.springs_cut, 0) << physics::ToolKey(tool);
    EXPECT_EQ(m.cautery_on_s, 0.0) << physics::ToolKey(tool);
    EXPECT_EQ(m.liver_damage_m2 + m.gallbladder_damage_m2, 0.0) << physics::ToolKey(tool);
    EXPECT_EQ(other.cautery().membrane().spring_cuts().size(), 0u) << physics::ToolKey(tool);
  }
}

}  // namespace
}  // namespace vesica::app
