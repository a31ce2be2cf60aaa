// The trainer's needle-biopsy mode driven as a trainee would, under Xvfb: a biopsy with the
// keyboard stylus taken during a breath hold, shown and stored beside the cholecystectomies; the
// Omni emulator killed mid-insertion; the switch between the two procedures at run time.

#include "app/needle_mode/needle_window.h"

#include <QVTKOpenGLNativeWidget.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <QAction>
#include <QApplication>
#include <QLabel>
#include <QPushButton>
#include <QTest>
#include <algorithm>
#include <filesystem>

#include "app/biopsy/biopsy_patient.h"
#include "app/biopsy/scripted_biopsy.h"
#include "app/history/metrics_panel.h"
#include "app/needle_mode/breathing_panel.h"
#include "app/needle_mode/ct_slice_widget.h"
#include "app/needle_mode/patient_view.h"
#include "app/records/session_store.h"
#include "app/scenario/scenario_loader.h"
#include "app/trainer/trainer_app.h"
#include "device/stylus/keyboard_stylus.h"
#include "device/stylus/stylus_recording.h"
#include "device/stylus/udp_stylus.h"
#include "tests/device/armsim_process.h"

namespace vesica::app::needle_mode {
namespace {

class NeedleWindowTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    patient_ = new std::shared_ptr<const biopsy::BiopsyPatient>(
        biopsy::LoadCommittedBiopsyPatient(std::filesystem::path(VESICA_SOURCE_DIR) / "data/patients"));
    surfaces_ =
        new std::vector<patient::OrganSurface>(patient::MeshPatient((*patient_)->volume.labels, DisplayMeshing()));
  }
  static void TearDownTestSuite() {
    delete surfaces_;
    delete patient_;
  }
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("vesica_needle_mode_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  NeedleModeOptions Options() const {
    NeedleModeOptions options;
    options.trainee_id = "resident-34";
    options.records_location = (dir_ / "sessions.sqlite").string();
    return options;
  }
  static biopsy::StylusPlacement Placement() {
    return biopsy::PlacementAtRightSide((*patient_)->model->liver.tumour_centre_m);
  }

  static std::shared_ptr<const biopsy::BiopsyPatient>* patient_;
  static std::vector<patient::OrganSurface>* surfaces_;
  std::filesystem::path dir_;
};
std::shared_ptr<const biopsy::BiopsyPatient>* NeedleWindowTest::patient_ = nullptr;
std::vector<patient::OrganSurface>* NeedleWindowTest::surfaces_ = nullptr;

TEST_F(NeedleWindowTest, AKeyboardBiopsyDuringABreathHoldIsShownAndStoredAsANeedleBiopsy) {
  const Eigen::Vector3d tumour = (*patient_)->model->liver.tumour_centre_m;
  auto keyboard = std::make_shared<device::KeyboardStylus>(biopsy::StartingStylus(Placement(), tumour));
  keyboard->Open();
  NeedleModeOptions options = Options();
  options.recordings_dir = dir_ / "recordings";
  NeedleWindow window(*patient_, *surfaces_, keyboard, {}, options);
  window.resize(1200, 700);
  window.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  // The patient holds the breath (H), as a radiologist asks before the needle goes in.
  QTest::keyClick(&window, Qt::Key_H);
  EXPECT_TRUE(window.breathing_panel()->holding());
  QTest::qWait(1500);  // the hold fades in over 1 s
  // Down the committed biopsy's line (between the 7th and 8th costal cartilages) to 7 mm short
  // of the tumour's centre, in 60 steps.
  const biopsy::ScriptedBiopsyPlan plan;
  std::string error;
  for (int i = 0; i <= 60; ++i) {
    physics::NeedlePose pose{plan.entry_above_skin_W + (plan.target_W - plan.entry_above_skin_W) * (i / 60.0),
                             plan.direction_W};
    ASSERT_TRUE(keyboard->SetPose(biopsy::StylusForNeedle(Placement(), pose), &error)) << error;
    QTest::qWait(25);
  }
  QTest::qWait(300);
  window.Tick();
  EXPECT_TRUE(window.runner().LatestNeedle().inside);
  EXPECT_FALSE(window.axial_slice()->image().isNull());
  EXPECT_FALSE(window.oblique_slice()->image().isNull());
  EXPECT_FALSE(window.metrics_panel()->isVisible());  // nothing to show before the sample
  // Space is the stylus' button 1: the biopsy.
  QTest::keyPress(&window, Qt::Key_Space);
  ASSERT_TRUE(QTest::qWaitFor([&] { return window.finished_shown(); }, 5000));
  QTest::keyRelease(&window, Qt::Key_Space);
  EXPECT_TRUE(window.metrics_panel()->isVisible());
  EXPECT_EQ(window.metrics_panel()->ValueText("metric_specimen"), "good specimen");
  EXPECT_EQ(window.metrics_panel()->ValueText("metric_insertion_attempts"), "1");
  EXPECT_EQ(window.metrics_panel()->ValueText("metric_nogo_crossings"), "0");
  EXPECT_TRUE(window.metrics_panel()->RowShown("metric_specimen"));
  EXPECT_FALSE(window.metrics_panel()->RowShown("metric_slips"));
  ASSERT_TRUE(QTest::qWaitFor([&] { return window.stored_session_id().has_value(); }, 15000)) << window.last_error();

  const auto store = OpenSessionStore(Options().records_location);
  const auto sessions = store->List("resident-34");
  ASSERT_EQ(sessions.size(), 1u);
  const SessionRecord& r = sessions[0].record;
  EXPECT_EQ(r.procedure, Procedure::kNeedleBiopsy);
  EXPECT_FALSE(r.unfinished);
  EXPECT_TRUE(r.metrics.biopsy_sampled);
  EXPECT_GE(r.metrics.sample_distance_m, 0.005);
  EXPECT_LT(r.metrics.sample_distance_m, 0.010);
  EXPECT_TRUE(r.metrics.success);
  EXPECT_EQ(r.metrics.insertion_attempts, 1);
  EXPECT_GT(r.metrics.max_force_N, 0.0);
  // The stylus stream was saved beside it: button 1 goes down in it when the sample was taken.
  ASSERT_FALSE(r.input_recording_path.empty());
  const device::StylusRecording stream = device::ReadStylusRecording(r.input_recording_path);
  const auto press = std::find_if(stream.samples.begin(), stream.samples.end(), [](const device::StylusSample& s) {
    return (s.state.buttons & device::kStylusButton1) != 0;
  });
  ASSERT_NE(press, stream.samples.end());
  EXPECT_NEAR(press->time_s, r.metrics.time_to_sample_s, 1e-9);
}

TEST_F(NeedleWindowTest, KillingTheOmniEmulatorMidInsertionZeroesTheForceAndTheWindowSaysSo) {
  const std::uint16_t device_port = device::testing::FreeUdpPort();
  const std::uint16_t host_port = device::testing::FreeUdpPort();
  ASSERT_NE(device_port, host_port);
  device::testing::ArmsimProcess omnisim;
  // The emulated hand plays the committed biopsy: 1 s above the skin, then in at 15 mm/s.
  const std::string biopsy = std::string(VESICA_SOURCE_DIR) + "/data/recordings/biopsy.csv";
  ASSERT_TRUE(omnisim.Start(VESICA_OMNISIM_PATH,
                            {"--port", std::to_string(device_port), "--host-port", std::to_string(host_port), "--hand",
                             "recording", biopsy, "--log-level", "warn"}));
  device::UdpStylusConfig config;
  config.device = {"127.0.0.1", device_port};
  config.local = {"127.0.0.1", host_port};
  auto udp = std::make_shared<device::UdpStylus>(config);
  ASSERT_NE(udp->Open(), device::DeviceStatus::kTransportError) << udp->last_error();
  NeedleWindow window(
      *patient_, *surfaces_, udp, [udp] { udp->Tick(); }, Options());
  window.resize(1000, 600);
  window.show();
  ASSERT_TRUE(QTest::qWaitFor([&] { return udp->Status() == device::DeviceStatus::kOk; }, 10000)) << udp->StatusText();
  ASSERT_TRUE(QTest::qWaitFor([&] { return udp->RenderedForce().norm() > 0.05; }, 10000))
      << "the needle going in should be felt";
  window.Tick();
  EXPECT_TRUE(window.device_label()->text().endsWith(": ok")) << window.device_label()->text().toStdString();

  omnisim.Kill(SIGKILL);
  // The stylus' own 9 ms loss timeout is tested against its tick times in tests/stylus; here the
  // window: the force is off and the status line says why, and nothing else breaks.
  ASSERT_TRUE(QTest::qWaitFor([&] { return udp->Status() == device::DeviceStatus::kLinkLost; }, 5000));
  EXPECT_EQ(udp->RenderedForce(), Eigen::Vector3d::Zero());
  window.Tick();
  EXPECT_TRUE(window.device_label()->text().contains("lost")) << window.device_label()->text().toStdString();
  EXPECT_TRUE(window.runner().error().empty()) << window.runner().error();
  QTest::qWait(200);
  EXPECT_EQ(udp->RenderedForce(), Eigen::Vector3d::Zero());
  std::string out;
  omnisim.Finish(&out);
}

TEST_F(NeedleWindowTest, SwitchingProcedureStoresTheCholecystectomyOpensTheNeedleModeAndComesBack) {
  TrainerOptions options;
  options.trainee_id = "resident-34";
  options.records_location = (dir_ / "sessions.sqlite").string();
  TrainerApp app(options, QSize(900, 550));
  ASSERT_TRUE(app.Open(DefaultScenarioPath())) << app.last_error();
  // The trainee moves the grasper: the session has begun.
  QWidget* gl = app.window()->findChild<QVTKOpenGLNativeWidget*>();
  QTest::qWait(200);
  for (int i = 0; i < 5; ++i) QTest::keyClick(gl, Qt::Key_D);
  QTest::qWait(300);
  // Session > Procedure > Needle biopsy, as the menu does it (deferred to the event loop).
  QAction* to_needle = app.window()->findChild<QAction*>("procedure_needle_biopsy");
  ASSERT_NE(to_needle, nullptr);
  ASSERT_TRUE(to_needle->isEnabled());
  to_needle->trigger();
  ASSERT_TRUE(QTest::qWaitFor([&] { return app.needle_window() != nullptr; }, 30000)) << app.last_error();
  EXPECT_EQ(app.window(), nullptr);  // the cholecystectomy's window, loops and arms are gone
  {
    const auto sessions = OpenSessionStore(options.records_location)->List("resident-34");
    ASSERT_EQ(sessions.size(), 1u);
    EXPECT_EQ(sessions[0].record.procedure, Procedure::kCholecystectomy);
    EXPECT_TRUE(sessions[0].record.unfinished);
  }
  // A biopsy with the keyboard stylus the trainer gave the needle mode: in along the committed
  // biopsy's line during a breath hold, the sample on Space.
  NeedleWindow& needle = *app.needle_window();
  auto* keyboard = dynamic_cast<device::KeyboardStylus*>(&needle.runner().stylus());
  ASSERT_NE(keyboard, nullptr);
  QTest::keyClick(&needle, Qt::Key_H);
  QTest::qWait(1200);
  const biopsy::ScriptedBiopsyPlan plan;
  std::string error;
  for (int i = 0; i <= 40; ++i) {
    const physics::NeedlePose pose{plan.entry_above_skin_W + (plan.target_W - plan.entry_above_skin_W) * (i / 40.0),
                                   plan.direction_W};
    ASSERT_TRUE(keyboard->SetPose(biopsy::StylusForNeedle(Placement(), pose), &error)) << error;
    QTest::qWait(25);
  }
  QTest::qWait(200);
  QTest::keyPress(&needle, Qt::Key_Space);
  ASSERT_TRUE(QTest::qWaitFor([&] { return needle.stored_session_id().has_value(); }, 15000)) << needle.last_error();
  QTest::keyRelease(&needle, Qt::Key_Space);
  {  // The records hold both procedures, in the order they were done.
    const auto sessions = OpenSessionStore(options.records_location)->List("resident-34");
    ASSERT_EQ(sessions.size(), 2u);
    EXPECT_EQ(sessions[0].record.procedure, Procedure::kCholecystectomy);
    EXPECT_EQ(sessions[1].record.procedure, Procedure::kNeedleBiopsy);
    EXPECT_TRUE(sessions[1].record.metrics.biopsy_sampled);
    EXPECT_FALSE(sessions[1].record.unfinished);
  }
  // Back to the cholecystectomy.
  QAction* back = needle.findChild<QAction*>("procedure_cholecystectomy");
  ASSERT_NE(back, nullptr);
  back->trigger();
  ASSERT_TRUE(QTest::qWaitFor([&] { return app.window() != nullptr; }, 30000)) << app.last_error();
  EXPECT_EQ(app.needle_window(), nullptr);
  // The finished biopsy was stored once: nothing more on the way back.
  EXPECT_EQ(OpenSessionStore(options.records_location)->List("resident-34").size(), 2u);
  app.Shutdown();
}

// At an arm station: the switch to the needle releases both haptic arms (vesica-armsim processes)
// with zero force, disabled and without a fault (not a vanished host that the arms' watchdog
// catches), and the cholecystectomy is in the records.
TEST_F(NeedleWindowTest, TheSwitchReleasesTheArmsWithZeroForceBeforeTheNeedleTakesOver) {
  const int base = device::testing::FreeArmBasePort();
  ASSERT_NE(base, 0);
  device::testing::ArmsimProcess left, right;
  ASSERT_TRUE(left.Start(VESICA_ARMSIM_PATH,
                         {"--node-id", "1", "--local-port", std::to_string(base), "--report", "--log-level", "warn"}));
  ASSERT_TRUE(right.Start(VESICA_ARMSIM_PATH, {"--node-id", "2", "--local-port", std::to_string(base + 2), "--report",
                                               "--log-level", "warn"}));
  TrainerOptions options;
  options.trainee_id = "resident-34";
  options.records_location = (dir_ / "sessions.sqlite").string();
  options.arms_udp_base_port = base;
  TrainerApp app(options, QSize(900, 550));
  ASSERT_TRUE(app.Open(std::filesystem::path(VESICA_SOURCE_DIR) / "data/scenarios/cholecystectomy-arms.toml"))
      << app.last_error();
  const auto both_ok = [&] {
    const std::string lines = app.window()->ArmStatusLines();
    return lines.find("left arm: ok") != std::string::npos && lines.find("right arm: ok") != std::string::npos;
  };
  ASSERT_TRUE(QTest::qWaitFor(both_ok, 20000)) << app.window()->ArmStatusLines();
  QTest::qWait(500);
  app.window()->findChild<QAction*>("procedure_needle_biopsy")->trigger();
  ASSERT_TRUE(QTest::qWaitFor([&] { return app.needle_window() != nullptr; }, 30000)) << app.last_error();
  QTest::qWait(500);  // the arms would fault on a lost host within this
  left.Kill(SIGTERM);
  right.Kill(SIGTERM);
  for (device::testing::ArmsimProcess* arm : {&left, &right}) {
    std::string report;
    EXPECT_EQ(arm->Finish(&report), 0);
    EXPECT_NE(report.find("actuator_force_N=0.000000,0.000000,0.000000"), std::string::npos) << report;
    EXPECT_EQ(report.find("state=enabled"), std::string::npos) << report;
    EXPECT_NE(report.find("fault=none"), std::string::npos) << report;
  }
  app.Shutdown();
}

}  // namespace
}  // namespace vesica::app::needle_mode
