// Scripted Calot sessions over each committed anatomical variant (issue 36's first acceptance
// point), through the real DissectionSession and instrument input only (calot_scripted_surgeon.h):
// a correct dissection reaches the critical view of safety and passes; clipping before it is
// flagged; the artery cut with no clip counts a bleed; a clip on the common bile duct is the
// critical error and ends the case. Each outcome is stored in a real SQLite records store, as the
// trainer stores a finished session, and read back. One test per variant and script, so ctest -j
// can spread the correct dissections (the long ones) over cores.

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <thread>

#include "app/calot/case_outcome.h"
#include "app/records/sqlite_session_store.h"
#include "app/render/scene_meshes.h"
#include "app/replay/calot_scripted_surgeon.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_session.h"
#include "app/session/dissection_setup.h"
#include "app/session/session_runner.h"
#include "device/input/replay_input.h"
#include "tests/calot_scripted/calot_seen_samples.h"
#include "tests/records/temp_dir.h"

namespace vesica::app {
namespace {

using calot::FindingKind;
using calot::StructureKind;

constexpr int kCysticDuct = 0, kCysticArtery = 1, kCommonBileDuct = 3;

struct Case {
  Scenario scenario;
  std::shared_ptr<const physics::DissectionModel> model;
  CalotSessionSetup setup;
};

Case LoadCase(const std::string& variant) {
  const std::filesystem::path path = DefaultScenarioPath().parent_path() / ("calot-" + variant + ".toml");
  Case c{LoadScenario(path), nullptr, {}};
  c.model = BuildDissectionModelFor(c.scenario, LoadSceneMeshes(c.scenario));
  c.setup = *CalotSessionSetupFor(c.scenario);
  return c;
}

CalotSurgeonSettings SettingsFor(const Case& c) {
  CalotSurgeonSettings settings;
  settings.scope_eye_W = c.setup.camera.p_Eye_W_m;
  return settings;
}

// Stores the session as the trainer does at its end (TrainerWindow::OnFinished: the metrics of
// the finished session under the scenario's name) in a fresh SQLite file; returns what reads back.
SessionRecord StoreAndReadBack(const Case& c, const SessionMetrics& metrics) {
  vesica::app::testing::TempDir dir("vesica-calot-scripted");
  SessionRecord record;
  record.trainee_id = "scripted-surgeon";
  record.scenario = c.scenario.name;
  record.started_unix_s = 1795406400;
  record.ended_unix_s = record.started_unix_s + static_cast<std::int64_t>(metrics.duration_s + 1);
  record.metrics = metrics;
  record.replay = true;
  {
    SqliteSessionStore store(dir.path() / "sessions.sqlite");
    store.Add(record);
  }
  SqliteSessionStore reopened(dir.path() / "sessions.sqlite", StoreAccess::kReadOnly);
  const auto stored = reopened.List("scripted-surgeon");
  EXPECT_EQ(stored.size(), 1u);
  if (stored.empty()) return {};
  EXPECT_EQ(stored[0].record, record);
  return stored[0].record;
}

// The frames replayed through the trainer's SessionRunner (not real time), to its end.
RunnerStatus ReplayThroughRunner(const Case& c, const std::vector<device::InputFrame>& frames) {
  device::InputRecording recording;
  recording.frames = frames;
  RunnerOptions options;
  options.real_time = false;
  options.end_after_s = frames.back().time_s + c.model->settings.time_step_s;
  options.calot = c.setup;
  SessionRunner runner(c.model, DefaultCauteryParams(), std::make_shared<device::ReplayInput>(recording), options);
  runner.Start();
  RunnerStatus s;
  for (int i = 0; i < 60000 && !(s = runner.Status()).finished; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  return s;
}

class CalotScriptedSessionTest : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override { case_ = std::make_unique<Case>(LoadCase(GetParam())); }
  std::unique_ptr<DissectionSession> NewSession() const {
    return std::make_unique<DissectionSession>(case_->model, DefaultCauteryParams(), case_->setup);
  }
  std::unique_ptr<Case> case_;
};

TEST_P(CalotScriptedSessionTest, ACorrectDissectionReachesTheCriticalViewAndPasses) {
  auto session = NewSession();
  const auto frames = RunScriptedCalot(*session, CalotScript::kCorrectDissection, SettingsFor(*case_));
  ASSERT_FALSE(frames.empty());
  const calot::CalotMetrics& metrics = *session->calot_metrics();
  // The view from the model's own state, independently of the metrics: the triangle's layer
  // cleared, the lower third off the bed, the duct and the artery each in view and bare.
  ASSERT_TRUE(metrics.CriticalViewTime().has_value()) << "never reached the critical view";
  std::printf("%s: critical view at %.2f s, session %.2f s (%zu steps)\n", GetParam().c_str(),
              *metrics.CriticalViewTime(), session->time_s(), frames.size());
  const calot::CalotSnapshot& last = session->calot_step()->last_snapshot();
  EXPECT_GE(session->calot_fat()->TriangleClearedFraction(), calot::CvsThresholds{}.fat_removed_min);
  EXPECT_GE(last.lower_third_separated_fraction, calot::CvsThresholds{}.lower_third_separated_min);
  ASSERT_TRUE(metrics.FirstClipTime().has_value());
  EXPECT_LT(*metrics.CriticalViewTime(), *metrics.FirstClipTime());
  EXPECT_TRUE(metrics.CriticalViewBeforeFirstClip());
  // Three clips on each cystic structure, two on the patient's side of the planned cut and one on
  // the gallbladder's, the cut between them; nothing bleeds or leaks, no bile duct touched.
  const auto& tubes = *session->calot_tubes();
  for (const int tube : {kCysticDuct, kCysticArtery}) {
    int patient_side = 0, gallbladder_side = 0;
    const double cut_s = last.structures[static_cast<std::size_t>(tube)].planned_cut_s;
    for (const auto& clip : tubes.clips())
      if (clip.tube == tube) ++(clip.s_m / tubes.TubeLength_m(tube) < cut_s ? patient_side : gallbladder_side);
    EXPECT_EQ(patient_side, 2) << "tube " << tube;
    EXPECT_EQ(gallbladder_side, 1) << "tube " << tube;
    int cuts = 0;
    for (const auto& cut : tubes.cuts()) cuts += cut.tube == tube;
    EXPECT_EQ(cuts, 1) << "tube " << tube;
  }
  for (const auto& clip : tubes.clips()) EXPECT_TRUE(clip.tube == kCysticDuct || clip.tube == kCysticArtery);
  EXPECT_FALSE(tubes.Bleeding());
  EXPECT_FALSE(tubes.BileLeaking());
  EXPECT_TRUE(metrics.AllClipsPlacedCorrectly(StructureKind::kCysticDuct));
  EXPECT_TRUE(metrics.AllClipsPlacedCorrectly(StructureKind::kCysticArtery));
  EXPECT_TRUE(metrics.AllDividedBetweenClips(StructureKind::kCysticDuct));
  EXPECT_TRUE(metrics.AllDividedBetweenClips(StructureKind::kCysticArtery));
  EXPECT_TRUE(metrics.Findings().empty()) << calot::OutcomeHeadline(calot::JudgeCase(metrics));
  const calot::CaseOutcome outcome = calot::JudgeCase(metrics);
  EXPECT_TRUE(outcome.passed) << (outcome.reasons.empty() ? "" : outcome.reasons[0].text);
  EXPECT_FALSE(session->case_ended());

  // Both structures visible, each apart from the other, at the end (an independent projection):
  // at least a fifth of each one's length seen where the other's picture does not cover it.
  const auto duct = testing::SeenSamples(case_->scenario, *case_->model, *session, kCysticDuct),
             artery = testing::SeenSamples(case_->scenario, *case_->model, *session, kCysticArtery);
  const auto samples_of = [&](int tube) { return static_cast<int>(tubes.TubeLength_m(tube) / 0.0005) + 1; };
  EXPECT_GE(testing::SeparateSamples(duct, artery), samples_of(kCysticDuct) / 5)
      << "of " << duct.size() << " duct samples seen";
  EXPECT_GE(testing::SeparateSamples(artery, duct), samples_of(kCysticArtery) / 5)
      << "of " << artery.size() << " artery samples seen";

  const SessionRecord stored = StoreAndReadBack(*case_, session->metrics());
  EXPECT_TRUE(stored.metrics.calot_step);
  EXPECT_TRUE(stored.metrics.cvs_achieved);
  EXPECT_DOUBLE_EQ(stored.metrics.cvs_time_s, *metrics.CriticalViewTime());
  EXPECT_TRUE(stored.metrics.cvs_before_first_clip);
  EXPECT_EQ(stored.metrics.cystic_duct_clips, 3);
  EXPECT_EQ(stored.metrics.cystic_artery_clips, 3);
  EXPECT_TRUE(stored.metrics.cystic_duct_clips_correct);
  EXPECT_TRUE(stored.metrics.cystic_artery_clips_correct);
  EXPECT_TRUE(stored.metrics.cystic_duct_divided_between_clips);
  EXPECT_TRUE(stored.metrics.cystic_artery_divided_between_clips);
  EXPECT_EQ(stored.metrics.bleeding_events, 0);
  EXPECT_EQ(stored.metrics.bile_leaks, 0);
  EXPECT_EQ(stored.metrics.bile_duct_injuries, 0);
  EXPECT_TRUE(stored.metrics.calot_passed);
}

TEST_P(CalotScriptedSessionTest, ClippingBeforeTheCriticalViewIsFlagged) {
  auto session = NewSession();
  const auto frames = RunScriptedCalot(*session, CalotScript::kClipBeforeCriticalView, SettingsFor(*case_));
  const calot::CalotMetrics& metrics = *session->calot_metrics();
  EXPECT_FALSE(metrics.CriticalViewTime().has_value());
  EXPECT_EQ(metrics.ClipsOn(StructureKind::kCysticDuct), 3);
  EXPECT_EQ(metrics.ClipsOn(StructureKind::kCysticArtery), 3);
  EXPECT_EQ(metrics.Count(FindingKind::kClipBeforeCriticalView), 6);  // each clip, on the duct and the artery
  EXPECT_EQ(metrics.Count(FindingKind::kCutBeforeCriticalView), 2);
  EXPECT_EQ(metrics.Count(FindingKind::kBleeding), 0);  // divided between clips
  EXPECT_EQ(metrics.Count(FindingKind::kBileDuctInjury), 0);
  const calot::CaseOutcome outcome = calot::JudgeCase(metrics);
  EXPECT_FALSE(outcome.passed);
  ASSERT_FALSE(outcome.reasons.empty());
  EXPECT_EQ(outcome.reasons[0].kind, calot::ReasonKind::kActedBeforeCriticalView);

  // The same hands through the trainer's runner give the same metrics, and they are stored.
  const RunnerStatus status = ReplayThroughRunner(*case_, frames);
  ASSERT_TRUE(status.finished);
  EXPECT_TRUE(status.error.empty()) << status.error;
  EXPECT_EQ(status.metrics.cystic_duct_clips, 3);
  EXPECT_EQ(status.metrics.cvs_before_first_clip, session->metrics().cvs_before_first_clip);
  const SessionRecord stored = StoreAndReadBack(*case_, status.metrics);
  EXPECT_TRUE(stored.metrics.calot_step);
  EXPECT_FALSE(stored.metrics.cvs_achieved);
  EXPECT_FALSE(stored.metrics.cvs_before_first_clip);
  EXPECT_EQ(stored.metrics.cystic_duct_clips, 3);
  EXPECT_EQ(stored.metrics.cystic_artery_clips, 3);
  EXPECT_EQ(stored.metrics.bleeding_events, 0);
  EXPECT_FALSE(stored.metrics.calot_passed);
}

TEST_P(CalotScriptedSessionTest, CuttingTheArteryWithoutClipsCountsABleed) {
  auto session = NewSession();
  const auto frames = RunScriptedCalot(*session, CalotScript::kArteryCutWithoutClips, SettingsFor(*case_));
  const auto& tubes = *session->calot_tubes();
  ASSERT_EQ(tubes.cuts().size(), 1u);
  EXPECT_EQ(tubes.cuts()[0].tube, kCysticArtery);
  EXPECT_TRUE(tubes.clips().empty());
  EXPECT_TRUE(tubes.Bleeding());  // the model: blood leaves the patient's stump
  const calot::CalotMetrics& metrics = *session->calot_metrics();
  EXPECT_EQ(metrics.Count(FindingKind::kBleeding), 1);
  EXPECT_FALSE(calot::JudgeCase(metrics).passed);

  const RunnerStatus status = ReplayThroughRunner(*case_, frames);
  ASSERT_TRUE(status.finished);
  EXPECT_TRUE(status.error.empty()) << status.error;
  const SessionRecord stored = StoreAndReadBack(*case_, status.metrics);
  EXPECT_TRUE(stored.metrics.calot_step);
  EXPECT_EQ(stored.metrics.bleeding_events, 1);
  EXPECT_EQ(stored.metrics.cystic_artery_clips, 0);
  EXPECT_FALSE(stored.metrics.cystic_artery_divided_between_clips);
  EXPECT_EQ(stored.metrics.bile_duct_injuries, 0);
  EXPECT_FALSE(stored.metrics.calot_passed);
}

TEST_P(CalotScriptedSessionTest, ClippingTheCommonBileDuctIsTheCriticalError) {
  auto session = NewSession();
  const auto frames = RunScriptedCalot(*session, CalotScript::kClipCommonBileDuct, SettingsFor(*case_));
  EXPECT_TRUE(session->case_ended());
  const auto& tubes = *session->calot_tubes();
  ASSERT_EQ(tubes.clips().size(), 1u);
  EXPECT_EQ(tubes.clips()[0].tube, kCommonBileDuct);
  const calot::CaseOutcome outcome = calot::JudgeCase(*session->calot_metrics());
  EXPECT_TRUE(outcome.critical_error);
  EXPECT_FALSE(outcome.passed);
  // The script stops at the step the case ended (the event carries the time at that step's end).
  EXPECT_NEAR(session->calot_metrics()->Findings().front().time_s,
              frames.back().time_s + case_->model->settings.time_step_s, 1e-9);

  // The trainer's runner finishes the session at the clip, as the app does, and stores it.
  const RunnerStatus status = ReplayThroughRunner(*case_, frames);
  ASSERT_TRUE(status.finished);
  EXPECT_TRUE(status.case_ended);
  ASSERT_TRUE(status.calot_metrics.has_value());
  EXPECT_TRUE(status.calot_metrics->CaseEnded());
  const SessionRecord stored = StoreAndReadBack(*case_, status.metrics);
  EXPECT_TRUE(stored.metrics.calot_step);
  EXPECT_EQ(stored.metrics.bile_duct_injuries, 1);
  EXPECT_EQ(stored.metrics.cystic_duct_clips, 0);
  EXPECT_FALSE(stored.metrics.calot_passed);
  EXPECT_FALSE(stored.metrics.success);
}

TEST(CalotScriptedSurgeonTest, RefusesASessionWithoutATriangleAndANonPositiveTipSpeed) {
  const Case c = LoadCase("standard");
  DissectionSession without(c.model, DefaultCauteryParams());  // no triangle in this session
  try {
    RunScriptedCalot(without, CalotScript::kCorrectDissection);
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no triangle"), std::string::npos) << e.what();
  }
  DissectionSession with(c.model, DefaultCauteryParams(), c.setup);
  CalotSurgeonSettings still;
  still.tip_speed_m_per_s = 0;
  try {
    RunScriptedCalot(with, CalotScript::kCorrectDissection, still);
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("tip_speed_m_per_s"), std::string::npos) << e.what();
  }
  EXPECT_EQ(with.time_s(), 0.0);  // nothing stepped
}

INSTANTIATE_TEST_SUITE_P(Variants, CalotScriptedSessionTest,
                         ::testing::Values("standard", "short-duct", "low-insertion", "anterior-artery"),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                           std::string name = param.param;
                           std::erase(name, '-');
                           return name;
                         });

}  // namespace
}  // namespace vesica::app
