// The trainer window driven like a user would with Qt's test tools: the default scenario, a
// session run from a recording, the metrics panel read at the end, the session found in the
// records database with the same metrics, its input saved and replayable; keys pause the
// session and move the instruments.

#include <QVTKOpenGLNativeWidget.h>
#include <gtest/gtest.h>

#include <QAction>
#include <QApplication>
#include <QLabel>
#include <QMouseEvent>
#include <QSurfaceFormat>
#include <QTest>
#include <QWheelEvent>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "app/history/metrics_panel.h"
#include "app/records/session_store.h"
#include "app/render/scene_meshes.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_setup.h"
#include "app/trainer/keyboard_control.h"
#include "app/trainer/trainer_app.h"
#include "app/trainer/trainer_window.h"
#include "device/input/input_recording.h"

namespace vesica::app {
namespace {

class TrainerGuiTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scenario_ = new Scenario(LoadScenario(DefaultScenarioPath()));
    meshes_ = new SceneMeshes(LoadSceneMeshes(*scenario_));
    model_ = BuildDissectionModelFor(*scenario_, *meshes_);
  }
  static void TearDownTestSuite() {
    model_.reset();
    delete meshes_;
    delete scenario_;
  }
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("vesica_trainer_gui_" + std::to_string(::getpid()));
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
  // The default scenario under another name, written to the test directory (mesh paths made
  // absolute).
  std::filesystem::path WriteVariantScenario(const std::string& name) const {
    std::ifstream in(DefaultScenarioPath());
    std::stringstream text;
    text << in.rdbuf();
    std::string toml = text.str();
    const std::string anatomy = (DefaultScenarioPath().parent_path().parent_path() / "anatomy").string() + "/";
    for (size_t at = toml.find("\"../anatomy/"); at != std::string::npos; at = toml.find("\"../anatomy/", at))
      toml.replace(at + 1, 11, anatomy);
    const size_t name_at = toml.find("name = \"" + scenario_->name + "\"");
    EXPECT_NE(name_at, std::string::npos);
    toml.replace(name_at, 9 + scenario_->name.size(), "name = \"" + name + "\"");
    const auto path = dir_ / "variant.toml";
    std::ofstream(path) << toml;
    return path;
  }
  static QString Label(TrainerWindow& w, const char* name) {
    auto* label = w.metrics_panel()->findChild<QLabel*>(name);
    return label ? label->text() : QString("<no label %1>").arg(name);
  }
  static Scenario* scenario_;
  static SceneMeshes* meshes_;
  static std::shared_ptr<const physics::DissectionModel> model_;
  std::filesystem::path dir_;
};
Scenario* TrainerGuiTest::scenario_ = nullptr;
SceneMeshes* TrainerGuiTest::meshes_ = nullptr;
std::shared_ptr<const physics::DissectionModel> TrainerGuiTest::model_;

TEST_F(TrainerGuiTest, ReplayedSessionShowsItsMetricsAndIsStored) {
  // The first 3 s of the committed dissection: approach, grasp, retraction.
  device::InputRecording rec =
      device::ReadInputRecording(std::filesystem::path(VESICA_SOURCE_DIR) / "data/recordings/dissection.csv");
  rec.frames.resize(600);
  const auto replay = dir_ / "head.csv";
  device::WriteInputRecording(replay, rec);

  TrainerOptions options;
  options.trainee_id = "resident-7";
  options.records_location = (dir_ / "sessions.sqlite").string();
  options.recordings_dir = dir_ / "recordings";
  options.replay_file = replay;
  options.real_time = false;
  auto w = MakeWindow(options);
  ASSERT_TRUE(QTest::qWaitFor([&] { return w->session_finished(); }, 120000)) << w->last_error();
  EXPECT_TRUE(w->last_error().empty()) << w->last_error();
  ASSERT_TRUE(w->stored_session_id().has_value());

  // The panel shows the stored metrics.
  auto store = OpenSessionStore(options.records_location);
  const auto sessions = store->List("resident-7");
  ASSERT_EQ(sessions.size(), 1u);
  const SessionRecord& r = sessions[0].record;
  EXPECT_EQ(r.scenario, scenario_->name);
  EXPECT_NEAR(r.metrics.duration_s, 3.0, 0.01);
  EXPECT_GT(r.metrics.path_length_left_m, 0.0);
  EXPECT_EQ(r.metrics.springs_total, static_cast<int>(model_->tissue.springs.size()));
  EXPECT_FALSE(r.metrics.gallbladder_free);
  EXPECT_EQ(Label(*w, "metric_slips"), QString::number(r.metrics.slips));
  EXPECT_TRUE(Label(*w, "metric_success").startsWith("no")) << Label(*w, "metric_success").toStdString();
  // The session's input was saved, and replays to the recording it came from.
  ASSERT_FALSE(r.input_recording_path.empty());
  const device::InputRecording saved = device::ReadInputRecording(r.input_recording_path);
  ASSERT_GE(saved.frames.size(), 599u);  // until the replay's last frame time, 2.995 s
  EXPECT_EQ(saved.frames[300].instruments[0].pose.jaw_angle_rad, rec.frames[300].instruments[0].pose.jaw_angle_rad);
  EXPECT_EQ(saved.frames[300].instruments[1].pose.insertion_m, rec.frames[300].instruments[1].pose.insertion_m);
  // The diagnostics overlay reports the three loops.
  const QString diag = w->diagnostics()->text();
  for (const char* loop : {"physics", "haptic", "render"}) EXPECT_TRUE(diag.contains(loop)) << diag.toStdString();
}

TEST_F(TrainerGuiTest, KeysMoveTheInstrumentsPauseAndEndTheSession) {
  TrainerOptions options;
  options.trainee_id = "resident-8";
  options.records_location = (dir_ / "sessions.sqlite").string();
  auto w = MakeWindow(options);
  QWidget* gl = w->findChild<QVTKOpenGLNativeWidget*>();
  ASSERT_NE(gl, nullptr);
  QTest::qWait(300);
  for (int i = 0; i < 10; ++i) QTest::keyClick(gl, Qt::Key_E);  // grasper in (E inserts... or withdraws)
  for (int i = 0; i < 5; ++i) QTest::keyClick(gl, Qt::Key_D);   // grasper yaw
  QTest::qWait(300);
  QTest::keyClick(gl, Qt::Key_P);
  QTest::qWait(100);
  EXPECT_TRUE(w->diagnostics()->text().contains("paused")) << w->diagnostics()->text().toStdString();
  QTest::keyClick(gl, Qt::Key_P);
  QTest::keyClick(gl, Qt::Key_Return);
  ASSERT_TRUE(QTest::qWaitFor([&] { return w->session_finished(); }, 30000));
  auto store = OpenSessionStore(options.records_location);
  const auto sessions = store->List("resident-8");
  ASSERT_EQ(sessions.size(), 1u);
  EXPECT_GT(sessions[0].record.metrics.path_length_left_m, 0.005);  // the keys moved the grasper tip
  EXPECT_EQ(sessions[0].record.metrics.path_length_right_m, 0.0);   // the hook was not touched
}

TEST_F(TrainerGuiTest, MouseDragsTurnTheInstrumentsAndTheWheelInsertsThem) {
  TrainerOptions options;
  options.trainee_id = "resident-11";
  options.records_location = (dir_ / "sessions.sqlite").string();
  options.recordings_dir = dir_ / "recordings";
  auto w = MakeWindow(options);
  QWidget* gl = w->findChild<QVTKOpenGLNativeWidget*>();
  ASSERT_NE(gl, nullptr);
  QTest::qWait(200);
  auto send_mouse = [&](QEvent::Type type, QPoint at, Qt::MouseButton button, Qt::MouseButtons held,
                        Qt::KeyboardModifiers modifiers = Qt::NoModifier) {
    QMouseEvent event(type, at, gl->mapToGlobal(at), button, held, modifiers);
    QApplication::sendEvent(gl, &event);
  };
  auto send_wheel = [&](QPoint at, int notches, Qt::MouseButtons held) {
    QWheelEvent event(at, gl->mapToGlobal(at), QPoint(), QPoint(0, 120 * notches), held, Qt::NoModifier,
                      Qt::NoScrollPhase, false);
    QApplication::sendEvent(gl, &event);
  };
  // Grasper: left button, 40 px left in two moves and 10 px up.
  send_mouse(QEvent::MouseButtonPress, {200, 200}, Qt::LeftButton, Qt::LeftButton);
  send_mouse(QEvent::MouseMove, {180, 195}, Qt::NoButton, Qt::LeftButton);
  send_mouse(QEvent::MouseMove, {160, 190}, Qt::NoButton, Qt::LeftButton);
  send_mouse(QEvent::MouseButtonRelease, {160, 190}, Qt::LeftButton, Qt::NoButton);
  // Hook: right button, 20 px right, and the wheel 3 notches away while dragging.
  send_mouse(QEvent::MouseButtonPress, {300, 200}, Qt::RightButton, Qt::RightButton);
  send_mouse(QEvent::MouseMove, {320, 200}, Qt::NoButton, Qt::RightButton);
  send_wheel({320, 200}, 3, Qt::RightButton);
  send_mouse(QEvent::MouseButtonRelease, {320, 200}, Qt::RightButton, Qt::NoButton);
  // Shift + drag pans the view, not an instrument; a plain move after the release moves nothing.
  send_mouse(QEvent::MouseButtonPress, {200, 200}, Qt::LeftButton, Qt::LeftButton, Qt::ShiftModifier);
  send_mouse(QEvent::MouseMove, {100, 100}, Qt::NoButton, Qt::LeftButton, Qt::ShiftModifier);
  send_mouse(QEvent::MouseButtonRelease, {100, 100}, Qt::LeftButton, Qt::NoButton, Qt::ShiftModifier);
  send_mouse(QEvent::MouseMove, {10, 10}, Qt::NoButton, Qt::NoButton);
  QTest::qWait(300);
  QTest::keyClick(gl, Qt::Key_Return);
  ASSERT_TRUE(QTest::qWaitFor([&] { return w->stored_session_id().has_value(); }, 30000)) << w->last_error();

  const auto sessions = OpenSessionStore(options.records_location)->List("resident-11");
  ASSERT_EQ(sessions.size(), 1u);
  const device::InputRecording rec = device::ReadInputRecording(sessions[0].record.input_recording_path);
  ASSERT_GE(rec.frames.size(), 2u);
  const auto& first = rec.frames.front().instruments;
  const auto& last = rec.frames.back().instruments;
  const KeyboardStep step;
  EXPECT_NEAR(last[0].pose.yaw_rad - first[0].pose.yaw_rad, 40 * step.angle_rad_per_pixel, 1e-12);
  EXPECT_NEAR(last[0].pose.pitch_rad - first[0].pose.pitch_rad, 10 * step.angle_rad_per_pixel, 1e-12);
  EXPECT_EQ(last[0].pose.insertion_m, first[0].pose.insertion_m);
  EXPECT_NEAR(last[1].pose.yaw_rad - first[1].pose.yaw_rad, -20 * step.angle_rad_per_pixel, 1e-12);
  EXPECT_EQ(last[1].pose.pitch_rad, first[1].pose.pitch_rad);
  EXPECT_NEAR(last[1].pose.insertion_m - first[1].pose.insertion_m, 3 * step.insertion_m_per_wheel_notch, 1e-12);
}

TEST_F(TrainerGuiTest, ResetAfterTheEndStartsASessionThatIsStoredToo) {
  TrainerOptions options;
  options.trainee_id = "resident-9";
  options.records_location = (dir_ / "sessions.sqlite").string();
  auto w = MakeWindow(options);
  QWidget* gl = w->findChild<QVTKOpenGLNativeWidget*>();
  ASSERT_NE(gl, nullptr);
  QTest::qWait(200);
  QTest::keyClick(gl, Qt::Key_Return);
  ASSERT_TRUE(QTest::qWaitFor([&] { return w->stored_session_id().has_value(); }, 30000)) << w->last_error();
  const std::int64_t first = *w->stored_session_id();
  QTest::keyClick(gl, Qt::Key_R);  // a new session from the rest state
  EXPECT_FALSE(w->session_finished());
  QTest::qWait(300);
  EXPECT_FALSE(w->session_finished());  // the first session's end does not end this one
  QTest::keyClick(gl, Qt::Key_P);       // pause, then end while paused
  QTest::keyClick(gl, Qt::Key_Return);
  ASSERT_TRUE(QTest::qWaitFor([&] { return w->stored_session_id().has_value(); }, 30000)) << w->last_error();
  EXPECT_NE(*w->stored_session_id(), first);
  EXPECT_EQ(OpenSessionStore(options.records_location)->List("resident-9").size(), 2u);
}

TEST_F(TrainerGuiTest, OpeningAnotherScenarioStoresTheRunningSessionAndRunsTheNewOne) {
  TrainerOptions options;
  options.trainee_id = "resident-10";
  options.records_location = (dir_ / "sessions.sqlite").string();
  TrainerApp app(options, QSize(800, 450));
  ASSERT_TRUE(app.Open(DefaultScenarioPath())) << app.last_error();
  TrainerWindow* first = app.window();
  ASSERT_NE(first, nullptr);
  EXPECT_TRUE(first->findChild<QAction*>("open_scenario")->isEnabled());
  QWidget* gl = first->findChild<QVTKOpenGLNativeWidget*>();
  QTest::qWait(300);
  for (int i = 0; i < 5; ++i) QTest::keyClick(gl, Qt::Key_D);  // move the grasper

  // A file that does not load: the open scenario's session goes on, the error names the file.
  const auto broken = dir_ / "broken.toml";
  std::ofstream(broken) << "[scenario]\nname = 3\n";
  EXPECT_FALSE(app.Open(broken));
  EXPECT_NE(app.last_error().find("broken.toml:2"), std::string::npos) << app.last_error();
  EXPECT_EQ(app.window(), first);
  EXPECT_EQ(first->last_error(), app.last_error());
  EXPECT_FALSE(first->session_finished());

  // Another scenario, chosen in the old window's menu: the window is replaced once the menu's
  // call has returned; the running session is ended and stored under the old scenario first.
  ASSERT_TRUE(first->RequestScenario(WriteVariantScenario("Cholecystectomy, stiff ligaments")));
  ASSERT_TRUE(QTest::qWaitFor([&] { return app.window() != first; }, 60000)) << app.last_error();
  TrainerWindow* second = app.window();
  EXPECT_EQ(second->scenario().name, "Cholecystectomy, stiff ligaments");
  EXPECT_TRUE(second->windowTitle().contains("stiff ligaments")) << second->windowTitle().toStdString();
  auto store = OpenSessionStore(options.records_location);
  auto sessions = store->List("resident-10");
  ASSERT_EQ(sessions.size(), 1u);
  EXPECT_EQ(sessions[0].record.scenario, scenario_->name);
  EXPECT_GT(sessions[0].record.metrics.path_length_left_m, 0.0);  // the keys moved the grasper

  // The new scenario's session runs and is stored under its name.
  QTest::qWait(300);
  EXPECT_FALSE(second->session_finished());
  QTest::keyClick(second->findChild<QVTKOpenGLNativeWidget*>(), Qt::Key_Return);
  ASSERT_TRUE(QTest::qWaitFor([&] { return second->stored_session_id().has_value(); }, 30000)) << second->last_error();
  sessions = store->List("resident-10");
  ASSERT_EQ(sessions.size(), 2u);
  EXPECT_EQ(sessions[1].record.scenario, "Cholecystectomy, stiff ligaments");
}

}  // namespace
}  // namespace vesica::app

int main(int argc, char** argv) {
  QSurfaceFormat::setDefaultFormat([] {
    auto format = QVTKOpenGLNativeWidget::defaultFormat();
    format.setSamples(0);
    return format;
  }());
  QApplication app(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
