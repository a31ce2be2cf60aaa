// The trainer's loops without a window: a replay through the threaded runner ends in the same
// state as the single-threaded replay; pause holds session time; reset starts over; the haptic
// loop runs beside physics.

#include "app/session/session_runner.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "app/render/scene_meshes.h"
#include "app/replay/session_replay.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_setup.h"
#include "app/session/live_input.h"
#include "device/input/input_recording.h"
#include "device/input/replay_input.h"

namespace vesica::app {
namespace {

using namespace std::chrono_literals;

class SessionRunnerTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const Scenario scenario = LoadScenario(DefaultScenarioPath());
    model_ = BuildDissectionModelFor(scenario, LoadSceneMeshes(scenario));
    device::InputRecording rec =
        device::ReadInputRecording(std::filesystem::path(VESICA_SOURCE_DIR) / "data/recordings/dissection.csv");
    rec.frames.resize(400);  // the first 2 s: approach and grasp
    head_ = new device::InputRecording(rec);
  }
  static void TearDownTestSuite() {
    model_.reset();
    delete head_;
  }
  // Real-time sessions on a loaded machine: wait for session time instead of sleeping a fixed
  // wall time (the first steps factor the gallbladder's system).
  static RunnerStatus WaitSessionTime(SessionRunner& runner, double t_s) {
    for (int i = 0; i < 6000; ++i) {
      const RunnerStatus s = runner.Status();
      if (s.session_time_s >= t_s) return s;
      std::this_thread::sleep_for(10ms);
    }
    ADD_FAILURE() << "session time did not reach " << t_s << " s in 60 s";
    return runner.Status();
  }
  static RunnerStatus WaitFinished(SessionRunner& runner) {
    for (int i = 0; i < 6000; ++i) {
      const RunnerStatus s = runner.Status();
      if (s.finished) return s;
      std::this_thread::sleep_for(10ms);
    }
    ADD_FAILURE() << "runner did not finish in 60 s";
    return runner.Status();
  }
  static std::shared_ptr<const physics::DissectionModel> model_;
  static device::InputRecording* head_;
};
std::shared_ptr<const physics::DissectionModel> SessionRunnerTest::model_;
device::InputRecording* SessionRunnerTest::head_ = nullptr;

TEST_F(SessionRunnerTest, ThreadedReplayEndsInTheSameStateAsTheHeadlessOne) {
  DissectionSession direct(model_, DefaultCauteryParams());
  device::ReplayInput replay(*head_);
  const ReplayOutcome outcome = RunReplay(direct, replay);

  RunnerOptions options;
  options.real_time = false;
  options.end_after_s = static_cast<double>(outcome.steps) * model_->settings.time_step_s - 1e-9;
  SessionRunner runner(model_, DefaultCauteryParams(), std::make_shared<device::ReplayInput>(*head_), options);
  runner.Start();
  const RunnerStatus s = WaitFinished(runner);
  EXPECT_TRUE(s.error.empty()) << s.error;
  EXPECT_EQ(s.session_time_s, direct.time_s());
  const SessionMetrics a = s.metrics, b = direct.metrics();
  EXPECT_EQ(a.path_length_left_m, b.path_length_left_m);
  EXPECT_EQ(a.path_length_right_m, b.path_length_right_m);
  EXPECT_EQ(a.max_force_N, b.max_force_N);
  EXPECT_EQ(a.mean_force_N, b.mean_force_N);
  EXPECT_GT(a.path_length_left_m, 0.0);
  const RenderFrame& frame = runner.LatestFrame();
  const RenderFrame expected = direct.MakeRenderFrame();
  ASSERT_EQ(frame.gallbladder_vertices.rows(), expected.gallbladder_vertices.rows());
  EXPECT_TRUE((frame.gallbladder_vertices.array() == expected.gallbladder_vertices.array()).all());
  EXPECT_EQ(frame.instruments[0].grasping, expected.instruments[0].grasping);
  // The recorded input replays to the same frames it was given.
  const device::InputRecording rec = runner.Recording();
  ASSERT_EQ(static_cast<long>(rec.frames.size()), outcome.steps);
  EXPECT_EQ(rec.frames[1].time_s, model_->settings.time_step_s);
  EXPECT_EQ(rec.frames[17].instruments[0].pose.insertion_m,
            device::ReplayInput(*head_).Sample(17 * model_->settings.time_step_s).instruments[0].pose.insertion_m);
  // The haptic loop ran beside physics.
  EXPECT_GT(s.haptic.rate_hz, 0.0);
}

TEST_F(SessionRunnerTest, PauseHoldsTimeResetStartsOverEndFinishes) {
  auto input = std::make_shared<LiveInput>();
  device::InstrumentInput hook;
  hook.pose.insertion_m = 0.05;
  input->Set(1, hook);
  input->Set(0, hook);
  RunnerOptions options;  // real time
  SessionRunner runner(model_, DefaultCauteryParams(), input, options);
  runner.Start();
  WaitSessionTime(runner, 0.3);
  runner.SetPaused(true);
  std::this_thread::sleep_for(200ms);  // let a step in flight finish
  const double paused_at = runner.Status().session_time_s;
  EXPECT_GE(paused_at, 0.3);
  std::this_thread::sleep_for(200ms);
  EXPECT_EQ(runner.Status().session_time_s, paused_at);
  EXPECT_TRUE(runner.Status().paused);
  runner.SetPaused(false);
  const int second = runner.Reset();
  RunnerStatus after = runner.Status();
  for (int i = 0; i < 6000 && after.session != second; ++i) {
    std::this_thread::sleep_for(10ms);
    after = runner.Status();
  }
  EXPECT_EQ(after.session, second);
  EXPECT_LT(after.session_time_s, paused_at);  // started over
  runner.End();
  const RunnerStatus s = WaitFinished(runner);
  EXPECT_TRUE(s.finished);
  EXPECT_TRUE(s.error.empty());
  EXPECT_GT(s.physics.rate_hz, 0.0);
}

TEST_F(SessionRunnerTest, EndWhilePausedFinishesWhereItStandsAndResetAfterEndStartsAgain) {
  auto input = std::make_shared<LiveInput>();
  RunnerOptions options;  // real time
  SessionRunner runner(model_, DefaultCauteryParams(), input, options);
  runner.Start();
  WaitSessionTime(runner, 0.1);
  runner.SetPaused(true);
  const double paused_at = runner.Status().session_time_s;
  runner.End();  // still paused: the session must end now, not when resumed
  const RunnerStatus ended = WaitFinished(runner);
  EXPECT_TRUE(ended.finished);
  EXPECT_TRUE(ended.paused);
  // At most the step that was in flight when the pause came, and nothing after the end.
  EXPECT_LE(ended.session_time_s, paused_at + 1.5 * model_->settings.time_step_s);
  std::this_thread::sleep_for(50ms);
  EXPECT_EQ(runner.Status().session_time_s, ended.session_time_s);

  // Reset after the end: a new session that runs on (the old End does not end it at once).
  runner.SetPaused(false);
  const int second = runner.Reset();
  RunnerStatus again = runner.Status();
  for (int i = 0; i < 1000 && !(again.session == second && again.session_time_s > 0.05); ++i) {
    std::this_thread::sleep_for(10ms);
    again = runner.Status();
  }
  EXPECT_EQ(again.session, second);
  EXPECT_GT(again.session_time_s, 0.05);
  EXPECT_FALSE(again.finished);
  runner.End();
  const RunnerStatus second_end = WaitFinished(runner);
  EXPECT_TRUE(second_end.finished);
  EXPECT_EQ(second_end.session, second);
}

// An input whose every sample takes 20 ms: four times the 5 ms step, so physics cannot keep up
// with the wall clock however fast the machine.
class SlowInput : public device::InstrumentInputSource {
 public:
  device::InputFrame Sample(double) override {
    std::this_thread::sleep_for(20ms);
    return {};
  }
};

TEST_F(SessionRunnerTest, PhysicsFallingBehindIsReportedNotHiddenInASlowerClock) {
  RunnerOptions options;  // real time
  SessionRunner runner(model_, DefaultCauteryParams(), std::make_shared<SlowInput>(), options);
  runner.Start();
  const RunnerStatus s = WaitSessionTime(runner, 0.1);  // 20 steps: at least 0.4 s of wall time
  ASSERT_GE(s.session_time_s, 0.1);
  // Each step of h = 5 ms took at least 20 ms: the wall clock ran at least 4 x the session time.
  const double h = model_->settings.time_step_s;
  const double steps = s.session_time_s / h;
  EXPECT_GE(s.wall_time_s, steps * 0.020);
  EXPECT_DOUBLE_EQ(s.physics_lag_s, s.wall_time_s - s.session_time_s);
  EXPECT_GE(s.physics_lag_s, steps * (0.020 - h));
  runner.End();
  WaitFinished(runner);
}

TEST_F(SessionRunnerTest, BadInputStopsPhysicsWithTheReason) {
  auto input = std::make_shared<LiveInput>();
  device::InstrumentInput bad;
  bad.pose.insertion_m = -1.0;
  input->Set(0, bad);
  RunnerOptions options;
  options.real_time = false;
  SessionRunner runner(model_, DefaultCauteryParams(), input, options);
  runner.Start();
  const RunnerStatus s = WaitFinished(runner);
  EXPECT_NE(s.error.find("instrument 0"), std::string::npos) << s.error;
}

}  // namespace
}  // namespace vesica::app
