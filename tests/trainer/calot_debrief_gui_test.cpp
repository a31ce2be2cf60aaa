// The trainer with Calot's triangle (issue 36), driven as a trainee would: a recorded case whose
// clip applier closes across the common bile duct ends there (the critical error), the debrief
// opens beside the metrics saying so, and the stored session carries the Calot columns; Enter
// ends a case with the step and opens the debrief too; T and the Session menu exchange the right
// hand's instrument.

#include <QVTKOpenGLNativeWidget.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <QAction>
#include <QDockWidget>
#include <QLabel>
#include <QStatusBar>
#include <QTest>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include "app/calot/debrief_screen.h"
#include "app/records/session_store.h"
#include "app/render/laparoscope_view.h"
#include "app/render/scene_meshes.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_setup.h"
#include "app/trainer/trainer_window.h"
#include "device/input/input_recording.h"
#include "physics/instrument/instrument_pose.h"

namespace vesica::app {
namespace {

class CalotDebriefGuiTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scenario_ =
        new Scenario(LoadScenario(std::filesystem::path(VESICA_SOURCE_DIR) / "data/scenarios/calot-standard.toml"));
    meshes_ = new SceneMeshes(LoadSceneMeshes(*scenario_));
    model_ = BuildDissectionModelFor(*scenario_, *meshes_);
  }
  static void TearDownTestSuite() {
    model_.reset();
    delete meshes_;
    delete scenario_;
  }
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("vesica_calot_gui_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::unique_ptr<TrainerWindow> MakeWindow(const TrainerOptions& options) {
    auto w = std::make_unique<TrainerWindow>(*scenario_, std::make_unique<LaparoscopeView>(*scenario_, *meshes_),
                                             model_, options);
    w->resize(800, 450);
    w->show();
    return w;
  }
  static bool DebriefShown(TrainerWindow& w) {
    auto* dock = w.findChild<QDockWidget*>("calot_debrief_dock");
    return dock && dock->isVisible();
  }
  // A recorded case: the right hand's port holds the clip applier from the start, its jaws open
  // and its tip 6 mm past the common bile duct's middle (the jaws' 18 mm span the duct), closed
  // at `close_at_s`; the recording lasts `length_s`. The grasper stays at its start.
  std::filesystem::path WriteCommonBileDuctClip(double close_at_s, double length_s) const {
    const CalotTubeConfig* bile = nullptr;
    for (const CalotTubeConfig& t : scenario_->calot_triangle->tubes)
      if (t.kind == physics::calot::TubeKind::kCommonBileDuct) bile = &t;
    const Eigen::Vector3d target = bile->points_m[1];
    const physics::InstrumentMount& right = model_->instruments[1];
    physics::InstrumentPose clip_applier = physics::AimAt(
        right.p_RemoteCentre_W, target, (target - right.p_RemoteCentre_W).norm() + 0.006, right.reference_direction_W);
    physics::InstrumentPose grasper;
    grasper.insertion_m = scenario_->instruments[0].initial_insertion_m;
    device::InputRecording rec;
    rec.scenario_name = scenario_->name;
    for (int k = 0; k * 0.005 <= length_s; ++k) {
      device::InputFrame f;
      f.time_s = k * 0.005;
      f.right_tool = physics::InstrumentTool::kClipApplier;
      clip_applier.jaw_angle_rad = f.time_s < close_at_s ? 0.5 : 0.0;
      f.instruments[0].pose = grasper;
      f.instruments[1].pose = clip_applier;
      rec.frames.push_back(f);
    }
    const auto path = dir_ / "cbd-clip.csv";
    device::WriteInputRecording(path, rec);
    return path;
  }
  static Scenario* scenario_;
  static SceneMeshes* meshes_;
  static std::shared_ptr<const physics::DissectionModel> model_;
  std::filesystem::path dir_;
};
Scenario* CalotDebriefGuiTest::scenario_ = nullptr;
SceneMeshes* CalotDebriefGuiTest::meshes_ = nullptr;
std::shared_ptr<const physics::DissectionModel> CalotDebriefGuiTest::model_;

TEST_F(CalotDebriefGuiTest, ClipOnTheCommonBileDuctEndsTheCaseWithTheDebrief) {
  TrainerOptions options;
  options.trainee_id = "resident-calot";
  options.records_location = (dir_ / "sessions.sqlite").string();
  options.replay_file = WriteCommonBileDuctClip(/*close_at_s=*/0.5, /*length_s=*/3.0);
  options.real_time = false;
  auto w = MakeWindow(options);
  ASSERT_NE(w->calot_debrief(), nullptr);
  EXPECT_FALSE(DebriefShown(*w));
  ASSERT_TRUE(QTest::qWaitFor([&] { return w->session_finished(); }, 120000)) << w->last_error();
  ASSERT_TRUE(QTest::qWaitFor([&] { return DebriefShown(*w); }, 5000));

  const std::string text = w->calot_debrief()->AllText().toStdString();
  std::printf("%s\n", text.c_str());
  // VESICA_CALOT_GUI_PNG=file.png saves the window with its debrief, to look at.
  if (const char* png = std::getenv("VESICA_CALOT_GUI_PNG")) w->grab().save(png);
  EXPECT_EQ(w->calot_debrief()->Outcome()->text().toStdString(), "Failed: bile duct injury");
  EXPECT_NE(text.find("Clip placed on the common bile duct at 0.5"), std::string::npos) << text;
  EXPECT_NE(text.find("before the critical view of safety: bile duct injury, the case ends"), std::string::npos)
      << text;
  EXPECT_NE(text.find("Bile duct injuries: 1"), std::string::npos) << text;

  // Stored with the Calot columns; the case ended at the clip, not at the recording's end.
  ASSERT_TRUE(QTest::qWaitFor([&] { return w->stored_session_id().has_value(); }, 60000)) << w->last_error();
  const auto sessions = OpenSessionStore(options.records_location)->List("resident-calot");
  ASSERT_EQ(sessions.size(), 1u);
  const SessionMetrics& m = sessions[0].record.metrics;
  EXPECT_TRUE(m.calot_step);
  EXPECT_EQ(m.bile_duct_injuries, 1);
  EXPECT_FALSE(m.cvs_achieved);
  EXPECT_FALSE(m.calot_passed);
  EXPECT_FALSE(m.success);
  EXPECT_GE(m.duration_s, 0.5);
  EXPECT_LT(m.duration_s, 0.6);
}

TEST_F(CalotDebriefGuiTest, EnterEndsTheCaseWithTheDebrief) {
  TrainerOptions options;
  options.trainee_id = "resident-enter";
  auto w = MakeWindow(options);
  QWidget* gl = w->findChild<QVTKOpenGLNativeWidget*>();
  QTest::qWait(300);
  EXPECT_FALSE(DebriefShown(*w));
  QTest::keyClick(gl, Qt::Key_Return);
  ASSERT_TRUE(QTest::qWaitFor([&] { return DebriefShown(*w); }, 10000)) << w->last_error();
  const std::string text = w->calot_debrief()->AllText().toStdString();
  EXPECT_NE(text.find("Critical view of safety: not reached"), std::string::npos) << text;
  EXPECT_EQ(text.find("bile duct injury, the case ends"), std::string::npos) << text;
  // A new session hides the last one's debrief.
  QTest::keyClick(gl, Qt::Key_R);
  EXPECT_FALSE(DebriefShown(*w));
}

TEST_F(CalotDebriefGuiTest, TAndTheMenuExchangeTheRightHandsInstrument) {
  TrainerOptions options;
  options.trainee_id = "resident-exchange";
  auto w = MakeWindow(options);
  QWidget* gl = w->findChild<QVTKOpenGLNativeWidget*>();
  QTest::qWait(200);
  EXPECT_EQ(w->right_tool(), physics::InstrumentTool::kCauteryHook);
  QTest::keyClick(gl, Qt::Key_T);
  EXPECT_EQ(w->right_tool(), physics::InstrumentTool::kClipApplier);
  EXPECT_EQ(w->statusBar()->currentMessage().toStdString(), "Right hand: clip applier");
  auto* exchange = w->findChild<QAction*>("exchange_right_tool");
  ASSERT_NE(exchange, nullptr);
  ASSERT_TRUE(exchange->isEnabled());
  exchange->trigger();
  EXPECT_EQ(w->right_tool(), physics::InstrumentTool::kScissors);
  EXPECT_EQ(w->statusBar()->currentMessage().toStdString(), "Right hand: scissors");
  exchange->trigger();
  EXPECT_EQ(w->right_tool(), physics::InstrumentTool::kCauteryHook);
}

}  // namespace
}  // namespace vesica::app
