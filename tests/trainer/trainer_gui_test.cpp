// The trainer window driven like a user would with Qt's test tools: the default scenario, a
// session run from a recording, the metrics panel read at the end, the session found in the
// records database with the same metrics, its input saved and replayable; keys pause the
// session and move the instruments.

#include <QVTKOpenGLNativeWidget.h>
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <QAction>
#include <QApplication>
#include <QStatusBar>
#include <QTableWidget>
#include <QLabel>
#include <QMouseEvent>
#include <QTest>
#include <QWheelEvent>
#include <filesystem>
#include <fstream>
#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "app/history/history_window.h"
#include "app/history/learning_curve_plot.h"
#include "app/history/metrics_panel.h"
#include "app/history/plot_metrics.h"
#include "app/records/metric_units.h"
#include "app/records/pending_sessions.h"
#include "app/records/session_store.h"
#include "app/render/scene_meshes.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_setup.h"
#include "app/trainer/keyboard_control.h"
#include "app/trainer/trainer_app.h"
#include "app/trainer/trainer_window.h"
#include "device/input/input_recording.h"
#include "firmware_protocol/transport/udp_transport.h"
#include "tests/device/armsim_process.h"

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
  // The first `frames` frames of the committed dissection (200 a second), written to the test folder.
  std::filesystem::path WriteReplayHead(std::size_t frames) const {
    device::InputRecording rec =
        device::ReadInputRecording(std::filesystem::path(VESICA_SOURCE_DIR) / "data/recordings/dissection.csv");
    rec.frames.resize(frames);
    const auto path = dir_ / ("head-" + std::to_string(frames) + ".csv");
    device::WriteInputRecording(path, rec);
    return path;
  }
  // Moves the grasper with the keyboard, so that the session has something in it.
  static void MoveGrasper(TrainerWindow& w) {
    QWidget* gl = w.findChild<QVTKOpenGLNativeWidget*>();
    QTest::qWait(200);
    for (int i = 0; i < 5; ++i) QTest::keyClick(gl, Qt::Key_D);
    QTest::qWait(300);
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
  // Stored off the GUI thread: a moment later.
  ASSERT_TRUE(QTest::qWaitFor([&] { return w->stored_session_id().has_value(); }, 60000)) << w->last_error();
  EXPECT_TRUE(w->last_error().empty()) << w->last_error();

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
  // Sessions are stored off the GUI thread: wait for the store, not just the end.
  ASSERT_TRUE(QTest::qWaitFor([&] { return w->stored_session_id().has_value(); }, 30000)) << w->last_error();
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
  EXPECT_NEAR(last[0].pose.yaw_rad - first[0].pose.yaw_rad, -40 * step.angle_rad_per_pixel, 1e-12);
  EXPECT_NEAR(last[0].pose.pitch_rad - first[0].pose.pitch_rad, 10 * step.angle_rad_per_pixel, 1e-12);
  EXPECT_EQ(last[0].pose.insertion_m, first[0].pose.insertion_m);
  EXPECT_NEAR(last[1].pose.yaw_rad - first[1].pose.yaw_rad, 20 * step.angle_rad_per_pixel, 1e-12);
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

// --- No finished session is ever lost -------------------------------------------------------

TEST_F(TrainerGuiTest, SessionIsStoredWhenItsInputRecordingCannotBeWritten) {
  std::ofstream(dir_ / "a-file") << "x";  // the recordings folder is a file: nothing can go there
  TrainerOptions options;
  options.trainee_id = "resident-20";
  options.records_location = (dir_ / "sessions.sqlite").string();
  options.recordings_dir = dir_ / "a-file" / "recordings";
  options.replay_file = WriteReplayHead(100);
  options.real_time = false;
  auto w = MakeWindow(options);
  ASSERT_TRUE(QTest::qWaitFor([&] { return w->stored_session_id().has_value(); }, 60000)) << w->last_error();
  const auto sessions = OpenSessionStore(options.records_location)->List("resident-20");
  ASSERT_EQ(sessions.size(), 1u);
  EXPECT_EQ(sessions[0].record.input_recording_path, "");
  EXPECT_NEAR(sessions[0].record.metrics.duration_s, 0.5, 0.01);
  const QString status = w->statusBar()->currentMessage();
  EXPECT_TRUE(status.contains("input recording was not saved")) << status.toStdString();
}

TEST_F(TrainerGuiTest, TraineeIdWithASlashGetsItsRecordingAndItsSession) {
  TrainerOptions options;
  options.trainee_id = "ward 3/ana";
  options.records_location = (dir_ / "sessions.sqlite").string();
  options.recordings_dir = dir_ / "recordings";
  options.replay_file = WriteReplayHead(100);
  options.real_time = false;
  auto w = MakeWindow(options);
  ASSERT_TRUE(QTest::qWaitFor([&] { return w->stored_session_id().has_value(); }, 60000)) << w->last_error();
  const auto sessions = OpenSessionStore(options.records_location)->List("ward 3/ana");
  ASSERT_EQ(sessions.size(), 1u);
  const std::filesystem::path recording = sessions[0].record.input_recording_path;
  EXPECT_EQ(recording.parent_path(), options.recordings_dir);
  EXPECT_TRUE(recording.filename().string().starts_with("ward_3_ana-session-")) << recording;
  EXPECT_GE(device::ReadInputRecording(recording).frames.size(), 99u);  // until the replay's last frame time
}

TEST_F(TrainerGuiTest, SessionsStartedInTheSameSecondKeepTheirOwnInput) {
  TrainerOptions options;
  options.trainee_id = "resident-21";
  options.records_location = (dir_ / "sessions.sqlite").string();
  options.recordings_dir = dir_ / "recordings";
  auto w = MakeWindow(options);
  QWidget* gl = w->findChild<QVTKOpenGLNativeWidget*>();
  // Several short sessions, as fast as the keys go: some start in the same second.
  std::vector<std::int64_t> ids;
  for (int i = 0; i < 3; ++i) {
    if (i > 0) QTest::keyClick(gl, Qt::Key_R);
    QTest::qWait(100);
    for (int k = 0; k <= i; ++k) QTest::keyClick(gl, Qt::Key_D);  // i + 1 yaw steps: each input differs
    QTest::qWait(300);  // physics samples the keys' pose before the end
    QTest::keyClick(gl, Qt::Key_Return);
    ASSERT_TRUE(QTest::qWaitFor([&] { return w->stored_session_id().has_value(); }, 30000)) << w->last_error();
    ids.push_back(*w->stored_session_id());
  }
  const auto sessions = OpenSessionStore(options.records_location)->List("resident-21");
  ASSERT_EQ(sessions.size(), 3u);
  const KeyboardStep step;
  const double start_yaw = LaparoscopeView(*scenario_, *meshes_).poses()[0].yaw_rad;
  for (int i = 0; i < 3; ++i) {
    const auto& r = sessions[static_cast<size_t>(i)].record;
    for (int j = 0; j < i; ++j) EXPECT_NE(r.input_recording_path, sessions[static_cast<size_t>(j)].record.input_recording_path);
    const device::InputRecording rec = device::ReadInputRecording(r.input_recording_path);
    ASSERT_FALSE(rec.frames.empty());
    // R put the grasper back, then D turned it by +angle_rad (toward the picture's right) i + 1 times.
    EXPECT_NEAR(rec.frames.back().instruments[0].pose.yaw_rad, start_yaw + (i + 1) * step.angle_rad, 1e-12)
        << "session " << i << " replays another session's input";
  }
}

TEST_F(TrainerGuiTest, SessionThatCannotBeStoredIsKeptAndStoredAtTheNextStart) {
  TrainerOptions options;
  options.trainee_id = "resident-22";
  options.records_location = (dir_ / "sessions.sqlite").string();
  options.saver.attempts = 2;
  options.saver.retry_wait = std::chrono::milliseconds(50);
  std::filesystem::create_directories(options.records_location);  // a folder where the file should be
  {
    auto w = MakeWindow(options);
    MoveGrasper(*w);
    QTest::keyClick(w->findChild<QVTKOpenGLNativeWidget*>(), Qt::Key_Return);
    ASSERT_TRUE(QTest::qWaitFor([&] { return !w->last_error().empty(); }, 30000));
    EXPECT_NE(w->last_error().find("kept in " + PendingSessionsPath(options.records_location).string()),
              std::string::npos)
        << w->last_error();
    EXPECT_FALSE(w->stored_session_id().has_value());
  }
  ASSERT_EQ(ReadPendingSessions(PendingSessionsPath(options.records_location)).size(), 1u);

  // The next start, with the location repaired: the kept session is stored, and the window says so.
  std::filesystem::remove(options.records_location);
  TrainerApp app(options, QSize(800, 450));
  ASSERT_TRUE(app.Open(DefaultScenarioPath())) << app.last_error();
  const QString status = app.window()->statusBar()->currentMessage();
  EXPECT_TRUE(status.contains("Stored 1 session(s) kept from an earlier run")) << status.toStdString();
  const auto sessions = OpenSessionStore(options.records_location)->List("resident-22");
  ASSERT_EQ(sessions.size(), 1u);
  EXPECT_GT(sessions[0].record.metrics.path_length_left_m, 0.0);
  EXPECT_FALSE(std::filesystem::exists(PendingSessionsPath(options.records_location)));
}

TEST_F(TrainerGuiTest, LockedDatabaseIsSavedOffTheGuiThreadOnceItIsFree) {
  TrainerOptions options;
  options.trainee_id = "resident-23";
  options.records_location = (dir_ / "sessions.sqlite").string();
  options.saver.attempts = 20;
  options.saver.retry_wait = std::chrono::milliseconds(100);
  OpenSessionStore(options.records_location);  // the file exists, as on a station in use
  // Another program holds the write lock (a second trainer, a long export).
  sqlite3* other = nullptr;
  ASSERT_EQ(sqlite3_open(options.records_location.c_str(), &other), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(other, "BEGIN EXCLUSIVE", nullptr, nullptr, nullptr), SQLITE_OK);

  auto w = MakeWindow(options);
  MoveGrasper(*w);
  QTest::keyClick(w->findChild<QVTKOpenGLNativeWidget*>(), Qt::Key_Return);
  ASSERT_TRUE(QTest::qWaitFor([&] { return w->session_finished(); }, 30000));
  // The window goes on (its timer renders) and says it is saving.
  EXPECT_TRUE(w->saving());
  QTest::qWait(500);
  EXPECT_TRUE(w->saving());
  EXPECT_TRUE(w->findChild<QLabel*>("saving")->isVisible());
  EXPECT_FALSE(w->stored_session_id().has_value());

  sqlite3_exec(other, "COMMIT", nullptr, nullptr, nullptr);
  sqlite3_close(other);
  ASSERT_TRUE(QTest::qWaitFor([&] { return w->stored_session_id().has_value(); }, 60000)) << w->last_error();
  QTest::qWait(50);
  EXPECT_FALSE(w->findChild<QLabel*>("saving")->isVisible());
  EXPECT_EQ(OpenSessionStore(options.records_location)->List("resident-23").size(), 1u);
}

TEST_F(TrainerGuiTest, QuitStoresTheRunningSessionAsUnfinished) {
  TrainerOptions options;
  options.trainee_id = "resident-24";
  options.records_location = (dir_ / "sessions.sqlite").string();
  auto w = MakeWindow(options);
  auto* quit = w->findChild<QAction*>("quit");
  ASSERT_NE(quit, nullptr);
  EXPECT_EQ(quit->shortcut(), QKeySequence(QKeySequence::Quit));
  EXPECT_EQ(quit->shortcut().toString(), "Ctrl+Q");
  MoveGrasper(*w);
  quit->trigger();
  EXPECT_FALSE(w->isVisible());
  const auto sessions = OpenSessionStore(options.records_location)->List("resident-24");
  ASSERT_EQ(sessions.size(), 1u);
  EXPECT_TRUE(sessions[0].record.unfinished);
  EXPECT_FALSE(sessions[0].record.replay);
  EXPECT_GT(sessions[0].record.metrics.path_length_left_m, 0.0);
}

// --- The haptic-arm path -------------------------------------------------------------------------

// The arms scenario on a station where another program holds the left arm's port: the window
// opens on the keyboard and its status line says why the arms are not driving, naming the port;
// a recording watched there still plays, and says the arms are not connected.
TEST_F(TrainerGuiTest, ArmsThatCannotStartAreSaidOnScreenNotASilentKeyboard) {
  const int base = device::testing::FreeArmBasePort();
  ASSERT_NE(base, 0);
  std::string error;
  auto squatter = fp::UdpTransport::open({.local_port = static_cast<std::uint16_t>(base + 1)}, error);
  ASSERT_TRUE(squatter) << error;
  const Scenario arms = LoadScenario(std::filesystem::path(VESICA_SOURCE_DIR) / "data/scenarios/cholecystectomy-arms.toml");
  TrainerOptions options;
  options.arms_udp_base_port = base;
  TrainerWindow w(arms, std::make_unique<LaparoscopeView>(arms, *meshes_), model_, options);
  w.show();
  const std::string status = w.statusBar()->currentMessage().toStdString();
  EXPECT_EQ(status.rfind("Haptic arms could not start: ", 0), 0u) << status;
  EXPECT_NE(status.find(std::to_string(base + 1)), std::string::npos) << status;
  EXPECT_NE(status.find("keyboard meanwhile"), std::string::npos) << status;
  EXPECT_NE(w.last_error().find(std::to_string(base + 1)), std::string::npos) << w.last_error();
  EXPECT_TRUE(w.ArmStatusLines().empty()) << w.ArmStatusLines();

  ASSERT_TRUE(w.StartSession(TrainerWindow::InputChoice::kReplay, WriteReplayHead(100)));
  const std::string replay_status = w.statusBar()->currentMessage().toStdString();
  EXPECT_NE(replay_status.find("haptic arms not connected"), std::string::npos) << replay_status;
  EXPECT_TRUE(QTest::qWaitFor([&] { return w.session_finished(); }, 60000));
}

// --- Honest records ------------------------------------------------------------------------------

TEST_F(TrainerGuiTest, ReplayIsStoredAsAReplayAndStaysOffTheLearningCurve) {
  TrainerOptions options;
  options.trainee_id = "resident-25";
  options.records_location = (dir_ / "sessions.sqlite").string();
  options.replay_file = WriteReplayHead(100);
  options.real_time = false;
  {
    auto w = MakeWindow(options);  // a replay: the recording drives, not the trainee
    ASSERT_TRUE(QTest::qWaitFor([&] { return w->stored_session_id().has_value(); }, 60000)) << w->last_error();
  }
  options.replay_file.clear();
  {
    auto w = MakeWindow(options);  // the trainee's own session
    MoveGrasper(*w);
    QTest::keyClick(w->findChild<QVTKOpenGLNativeWidget*>(), Qt::Key_Return);
    ASSERT_TRUE(QTest::qWaitFor([&] { return w->stored_session_id().has_value(); }, 30000)) << w->last_error();
  }
  auto store = OpenSessionStore(options.records_location);
  const auto sessions = store->List("resident-25");
  ASSERT_EQ(sessions.size(), 2u);
  EXPECT_TRUE(sessions[0].record.replay);
  EXPECT_FALSE(sessions[1].record.replay);
  HistoryWindow history(*store);
  ASSERT_TRUE(history.SelectTrainee("resident-25"));
  EXPECT_EQ(history.Table()->rowCount(), 2);
  EXPECT_EQ(history.Table()->item(0, 5)->text(), "replay");
  EXPECT_EQ(history.Plot()->Points().size(), 1u);  // only the trainee's own session
  EXPECT_TRUE(history.StatusText().contains("1 replay(s) listed, not plotted")) << history.StatusText().toStdString();
}

// A physics step of 20 us cannot keep up with the wall clock on any machine (one step of the
// coupled scene costs far more): the window says how far behind it is while the trainee works,
// and the record keeps the lag beside the wall-clock duration the trainee lived.
TEST_F(TrainerGuiTest, PhysicsFallingBehindIsShownAndRecorded) {
  physics::DissectionModelInputs in = MakeDissectionInputs(*scenario_, *meshes_);
  in.settings.time_step_s = 2e-5;
  in.liver_bem.cache_path = BemCachePath(*scenario_).string();
  const auto slow_model = physics::BuildDissectionModel(in);

  TrainerOptions options;  // real time, the keyboard
  options.trainee_id = "resident-31";
  options.records_location = (dir_ / "sessions.sqlite").string();
  auto w = std::make_unique<TrainerWindow>(*scenario_, std::make_unique<LaparoscopeView>(*scenario_, *meshes_),
                                           slow_model, options);
  w->resize(800, 450);
  w->show();
  auto* lag = w->findChild<QLabel*>("physics_lag");
  ASSERT_NE(lag, nullptr);
  MoveGrasper(*w);
  ASSERT_TRUE(QTest::qWaitFor([&] { return lag->isVisible(); }, 20000)) << "no lag shown";
  EXPECT_TRUE(lag->text().startsWith("physics behind real time by ")) << lag->text().toStdString();
  QTest::qWait(500);
  QTest::keyClick(w->findChild<QVTKOpenGLNativeWidget*>(), Qt::Key_Return);
  ASSERT_TRUE(QTest::qWaitFor([&] { return w->stored_session_id().has_value(); }, 30000)) << w->last_error();
  EXPECT_FALSE(lag->isVisible());  // a finished session is not behind

  auto store = OpenSessionStore(options.records_location);
  const auto sessions = store->List("resident-31");
  ASSERT_EQ(sessions.size(), 1u);
  const SessionRecord& r = sessions[0].record;
  // The duration is the trainee's wall-clock time; the tissue lived less than a fifth of it.
  EXPECT_GT(r.metrics.duration_s, 1.0);
  EXPECT_GT(r.physics_lag_s, 0.8 * r.metrics.duration_s);
  EXPECT_LT(r.physics_lag_s, r.metrics.duration_s);
}

TEST(TrainerUnitsTest, HistoryPlotsInTheUnitsOfTheCsvExportAndTheRecordsTool) {
  for (const PlotMetric& plotted : kPlotMetrics) {
    const MetricDisplayUnit* unit = FindMetricDisplayUnit(plotted.key);
    ASSERT_NE(unit, nullptr) << plotted.key;
    EXPECT_STREQ(plotted.unit, unit->unit) << plotted.key;
    EXPECT_EQ(plotted.scale, unit->scale) << plotted.key;
  }
}

TEST_F(TrainerGuiTest, ResetPutsTheInstrumentsBackWithTheTissue) {
  TrainerOptions options;
  options.trainee_id = "resident-26";
  options.records_location = (dir_ / "sessions.sqlite").string();
  options.recordings_dir = dir_ / "recordings";
  auto w = MakeWindow(options);
  QWidget* gl = w->findChild<QVTKOpenGLNativeWidget*>();
  MoveGrasper(*w);
  QTest::keyClick(gl, Qt::Key_M);  // pedal down
  QTest::keyClick(gl, Qt::Key_R);
  QTest::qWait(300);
  QTest::keyClick(gl, Qt::Key_Return);
  ASSERT_TRUE(QTest::qWaitFor([&] { return w->stored_session_id().has_value(); }, 30000)) << w->last_error();
  const auto sessions = OpenSessionStore(options.records_location)->List("resident-26");
  ASSERT_EQ(sessions.size(), 1u);  // the session before R was not ended: only the new one
  const device::InputRecording rec = device::ReadInputRecording(sessions[0].record.input_recording_path);
  ASSERT_FALSE(rec.frames.empty());
  const auto start = LaparoscopeView(*scenario_, *meshes_).poses();  // where the scenario puts them
  for (const auto& frame : {rec.frames.front(), rec.frames.back()}) {
    EXPECT_EQ(frame.instruments[0].pose.yaw_rad, start[0].yaw_rad);
    EXPECT_EQ(frame.instruments[0].pose.insertion_m, start[0].insertion_m);
    EXPECT_FALSE(frame.instruments[1].pedal);
  }
  EXPECT_EQ(sessions[0].record.metrics.path_length_left_m, 0.0);
}

// --- The real trainer, as a process -----------------------------------------------------------------

// Starts vesica-trainer with `args` and `env` changes (nullopt: unset); stdout and stderr go to
// `log`. Returns the child's pid.
pid_t StartTrainer(const std::vector<std::string>& args, const std::map<std::string, std::optional<std::string>>& env,
                   const std::filesystem::path& log) {
  std::vector<std::string> argv{VESICA_TRAINER_EXE};
  argv.insert(argv.end(), args.begin(), args.end());
  const pid_t pid = fork();
  if (pid == 0) {
    for (const auto& [name, value] : env) value ? setenv(name.c_str(), value->c_str(), 1) : unsetenv(name.c_str());
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, STDOUT_FILENO);
    dup2(fd, STDERR_FILENO);
    std::vector<char*> pointers;
    for (auto& a : argv) pointers.push_back(a.data());
    pointers.push_back(nullptr);
    execv(pointers[0], pointers.data());
    _exit(127);
  }
  return pid;
}

// Waits for the child; its exit code, -1 when a signal ended it, -2 when it ran past `timeout_s`
// (then it is killed).
int WaitTrainer(pid_t pid, int timeout_s) {
  for (int i = 0; i < timeout_s * 100; ++i) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
  return -2;
}

std::string ReadText(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST_F(TrainerGuiTest, XdgDataHomeThatIsAFileIsAnErrorAtStart) {
  const auto xdg = dir_ / "xdg-is-a-file";
  std::ofstream(xdg) << "x";
  const auto log = dir_ / "trainer.log";
  const pid_t pid = StartTrainer({"--quit-after-ms", "3000", "--trainee", "resident-27"},
                                 {{"XDG_DATA_HOME", xdg.string()}, {"VESICA_RECORDS_DB", std::nullopt}}, log);
  EXPECT_EQ(WaitTrainer(pid, 120), 2);
  const std::string text = ReadText(log);
  EXPECT_NE(text.find("the records database cannot be used"), std::string::npos) << text;
  EXPECT_NE(text.find("XDG_DATA_HOME=" + xdg.string() + ", which must be a folder"), std::string::npos) << text;
  EXPECT_NE(text.find("Not a directory"), std::string::npos) << text;
}

TEST_F(TrainerGuiTest, BemCacheThatCannotBeWrittenRunsUncachedAndSaysSoOnce) {
  // The liver's cache file is a directory (a leftover, a mistake): the trainer runs uncached,
  // warns once, and the session is stored.
  const auto cache_dir = dir_ / "cache";
  std::filesystem::create_directories(cache_dir);
  ::setenv("VESICA_CACHE_DIR", cache_dir.c_str(), 1);
  const auto cache_file = BemCachePath(*scenario_);
  ::unsetenv("VESICA_CACHE_DIR");
  std::filesystem::create_directories(cache_file);
  const auto db = dir_ / "sessions.sqlite";
  const auto log = dir_ / "trainer.log";
  const pid_t pid = StartTrainer({"--replay", WriteReplayHead(100).string(), "--fast", "--records", db.string(),
                                  "--trainee", "resident-29", "--quit-after-ms", "15000"},
                                 {{"VESICA_CACHE_DIR", cache_dir.string()}}, log);
  EXPECT_EQ(WaitTrainer(pid, 120), 0) << ReadText(log);
  const std::string text = ReadText(log);
  const std::string warning = "running without the cache";
  const auto first = text.find(warning);
  ASSERT_NE(first, std::string::npos) << text;
  EXPECT_EQ(text.find(warning, first + 1), std::string::npos) << "said more than once:\n" << text;
  EXPECT_NE(text.find(cache_file.string()), std::string::npos) << text;
  EXPECT_EQ(OpenSessionStore(db.string())->List("resident-29").size(), 1u) << text;
}

TEST_F(TrainerGuiTest, SigtermMidSessionStoresTheSessionAsUnfinished) {
  const auto db = dir_ / "sessions.sqlite";
  const auto log = dir_ / "trainer.log";
  // A replay in real time: the session is still running when the signal comes.
  const pid_t pid = StartTrainer({"--replay", WriteReplayHead(2000).string(), "--records", db.string(),
                                  "--recordings-dir", "none", "--trainee", "resident-28"},
                                 {}, log);
  // Wait until the session runs (the window is up), then a little more so that the tools moved.
  bool running = false;
  for (int i = 0; i < 12000 && !running; ++i) {
    running = ReadText(log).find("connective-tissue springs") != std::string::npos;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(running) << ReadText(log);
  std::this_thread::sleep_for(std::chrono::seconds(3));
  ASSERT_EQ(kill(pid, SIGTERM), 0);
  EXPECT_EQ(WaitTrainer(pid, 60), 0) << ReadText(log);
  const auto sessions = OpenSessionStore(db.string())->List("resident-28");
  ASSERT_EQ(sessions.size(), 1u) << ReadText(log);
  EXPECT_TRUE(sessions[0].record.unfinished);
  EXPECT_TRUE(sessions[0].record.replay);
  EXPECT_GT(sessions[0].record.metrics.duration_s, 0.0);
}

}  // namespace
}  // namespace vesica::app
