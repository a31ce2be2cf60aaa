// Tools > Calibrate arms driven as a technician would, under Xvfb: the panel scans the arms, runs
// a whole calibration of an emulated random arm (the motion prompt answered, the progress shown
// step by step) whose recovered values are the arm's ground truth within issue 32's tolerances,
// with the checks in its table and the report files on disk; Abort mid-step leaves the arm
// disabled on the calibration stored before. In the trainer window the panel takes the arms from
// the session (the bridge lets go of vesica-armsim's ports) and gives them back when it closes.

#include "app/trainer/calibration_panel.h"

#include <gtest/gtest.h>

#include <QAction>
#include <QApplication>
#include <QComboBox>
#include <QLabel>
#include <QListWidget>
#include <QMenuBar>
#include <QMessageBox>
#include <QPlainTextEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QTableWidget>
#include <QTest>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include "app/calibrate/commands.h"
#include "app/calibrate/exit_codes.h"
#include "app/render/scene_meshes.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_setup.h"
#include "app/trainer/calibration_bus.h"
#include "app/trainer/calibration_panel_ui.h"
#include "app/trainer/trainer_window.h"
#include "device/calibration/calibration_abort.h"
#include "firmware_protocol/emulator/arm_ground_truth.h"
#include "firmware_protocol/node/parameter_table.h"
#include "tests/device/armsim_process.h"

namespace vesica::app {
namespace {

namespace c = calibrate;
namespace emu = fp::emulator;
constexpr double kDeg = std::numbers::pi / 180.0;
constexpr const char* kJoint[3] = {"yaw", "pitch", "insertion"};
constexpr int kCommandTimeoutMs = 300000;  // a loaded two-core host: generous, never a speed test

std::string FreshDir(const std::string& name) {
  const auto d =
      std::filesystem::temp_directory_path() / ("vesica_calibration_panel_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::remove_all(d);
  return d.string();
}

c::ToolOptions Emulated(std::uint64_t seed, const std::string& dir) {
  c::ToolOptions o;
  o.bus.kind = c::BusSpec::Kind::kEmulated;
  o.bus.emulated_seed = seed;
  o.data_dir = dir;
  o.date_s = 1790000000;
  return o;
}

template <typename W>
W* Child(QWidget& parent, const char* name) {
  W* w = parent.findChild<W*>(name);
  EXPECT_NE(w, nullptr) << name;
  return w;
}

bool WaitIdle(CalibrationPanel& panel) {
  return QTest::qWaitFor([&] { return !panel.busy(); }, kCommandTimeoutMs);
}

// The motion prompt, once it is up: checks what it says and presses `button`.
void AnswerPrompt(CalibrationPanel& panel, QMessageBox::StandardButton button) {
  QMessageBox* box = nullptr;
  ASSERT_TRUE(QTest::qWaitFor([&] { return (box = panel.findChild<QMessageBox*>("motion_prompt")) != nullptr; },
                              kCommandTimeoutMs));
  const std::string text = box->text().toStdString();
  EXPECT_NE(text.find("arm 1 (node 1, serial 0x5E51CA01) will move"), std::string::npos) << text;
  EXPECT_NE(text.find("friction: "), std::string::npos) << text;
  EXPECT_NE(text.find("0.60 A"), std::string::npos) << text;
  EXPECT_TRUE(box->isModal());
  QTest::mouseClick(box->button(button), Qt::LeftButton);
}

// The guided hand motion's prompt through the panel's ToolUi: the worker keeps asking (the link is
// serviced between calls) and gets kWait until the panel's button answers, then that answer once;
// an answer left from an earlier prompt is not the next prompt's; the abort flag stops it.
TEST(CalibrationPanelUi, AGuidedHandPromptWaitsForThePersonWithoutBlockingTheWorker) {
  QObject gui;
  std::vector<c::HandPrompt> shown;
  double live = -1.0;
  CalibrationPanelHandlers handlers;
  handlers.progress = [](int, const std::string&, double, double) {};
  handlers.note = [](const std::string&) {};
  handlers.ask = [](const c::MotionNotice&, std::function<void(bool)> answer) { answer(false); };
  handlers.hand_prompt = [&](const c::HandPrompt& p) { shown.push_back(p); };
  handlers.hand_live = [&](const c::HandPrompt&, double v) { live = v; };
  std::atomic<bool> abort{false};
  CalibrationPanelUi ui(&gui, handlers, &abort);

  c::HandPrompt prompt;
  prompt.arm = 1;
  prompt.step = "jaw span";
  prompt.instruction = "Close the jaw handle fully and hold it there.";
  prompt.unit = "counts";
  prompt.prompt_count = 2;
  std::atomic<int> calls{0};
  std::atomic<bool> done{false};
  c::HandAnswer answer = c::HandAnswer::kWait;
  const auto ask = [&](const c::HandPrompt& p) {
    done = false;
    calls = 0;
    return std::thread([&, p] {
      do {
        answer = ui.GuideHand(p, 1000.0 + calls);
        ++calls;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      } while (answer == c::HandAnswer::kWait);
      done = true;
    });
  };
  std::thread worker = ask(prompt);
  ASSERT_TRUE(QTest::qWaitFor([&] { return shown.size() == 1 && live >= 1000.0; }, 10000));
  EXPECT_EQ(shown[0].instruction, prompt.instruction);
  ASSERT_TRUE(QTest::qWaitFor([&] { return calls > 50; }, 10000));
  EXPECT_FALSE(done) << "answered before anyone pressed a button";
  ui.HandAnswered(c::HandAnswer::kAccept);
  worker.join();
  EXPECT_EQ(answer, c::HandAnswer::kAccept);

  // A retry pressed for prompt 1 that the worker had not taken is not prompt 2's answer.
  ui.HandAnswered(c::HandAnswer::kRetry);
  prompt.prompt_index = 1;
  EXPECT_EQ(ui.GuideHand(prompt, 2000.0), c::HandAnswer::kWait);
  ASSERT_TRUE(QTest::qWaitFor([&] { return shown.size() == 2; }, 10000));
  EXPECT_EQ(shown[1].prompt_index, 1);
  ui.HandAnswered(c::HandAnswer::kRetry);
  EXPECT_EQ(ui.GuideHand(prompt, 2001.0), c::HandAnswer::kRetry);
  EXPECT_EQ(ui.GuideHand(prompt, 2002.0), c::HandAnswer::kWait);  // taken once
  abort = true;
  EXPECT_EQ(ui.GuideHand(prompt, 2003.0), c::HandAnswer::kAbort);
}

TEST(CalibrationBusOf, TheTrainersArmsWhereItDrivesThem) {
  Scenario scenario;
  scenario.instruments.resize(2);
  // No arm named (the default scenario): the emulated arms, vesica-armsim on the trainer's port.
  c::BusSpec spec = CalibrationBusOf(scenario, 23456);
  EXPECT_EQ(spec.kind, c::BusSpec::Kind::kUdp);
  EXPECT_EQ(spec.udp_host, "127.0.0.1");
  EXPECT_EQ(spec.udp_base_port, 23456);
  scenario.instruments[0].input = InputKind::kEmulatedArm;
  EXPECT_EQ(CalibrationBusOf(scenario, 20000).kind, c::BusSpec::Kind::kUdp);
  // Arms on SocketCAN: that interface.
  scenario.instruments[0].input = InputKind::kCanArm;
  scenario.instruments[0].can_interface = "can1";
  scenario.instruments[1].input = InputKind::kCanArm;
  scenario.instruments[1].can_interface = "can1";
  spec = CalibrationBusOf(scenario, 20000);
  EXPECT_EQ(spec.kind, c::BusSpec::Kind::kCan);
  EXPECT_EQ(spec.can_interface, "can1");
  // Two interfaces: the panel opens one bus, and says which two.
  scenario.instruments[1].can_interface = "can2";
  try {
    CalibrationBusOf(scenario, 20000);
    ADD_FAILURE() << "two interfaces accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("can1 and can2"), std::string::npos) << e.what();
  }
}

TEST(CalibrationPanel, RunsAWholeCalibrationOfAnEmulatedArmToItsGroundTruth) {
  constexpr std::uint64_t kSeed = 21;
  const std::string dir = FreshDir("whole");
  CalibrationPanel panel(Emulated(kSeed, dir));
  panel.show();
  // It scans as it opens: both arms, as `vesica-calibrate scan` prints them.
  ASSERT_TRUE(WaitIdle(panel));
  ASSERT_EQ(panel.last_outcome().exit_code, c::kExitOk) << panel.last_outcome().text;
  const std::string arms = Child<QPlainTextEdit>(panel, "arms_view")->toPlainText().toStdString();
  EXPECT_NE(arms.find("bus: emulated arms (seed 21)"), std::string::npos) << arms;
  EXPECT_NE(arms.find("arm 1 (node 1, serial 0x5E51CA01)"), std::string::npos) << arms;
  EXPECT_NE(arms.find("arm 2 (node 2, serial 0x5E51CA02)"), std::string::npos) << arms;
  EXPECT_EQ(Child<QLabel>(panel, "bus_label")->text().toStdString(), "Bus: emulated arms (seed 21)");

  // Info on arm 1: its stored values (a blank board: none yet).
  QTest::mouseClick(Child<QPushButton>(panel, "info_button"), Qt::LeftButton);
  ASSERT_TRUE(WaitIdle(panel));
  EXPECT_EQ(panel.last_outcome().exit_code, c::kExitOk) << panel.last_outcome().text;
  EXPECT_NE(Child<QPlainTextEdit>(panel, "arms_view")->toPlainText().toStdString().find("stored values:"),
            std::string::npos);

  // Calibrate arm 1, all joints, all steps; yes to the prompt.
  QTest::mouseClick(Child<QPushButton>(panel, "calibrate_button"), Qt::LeftButton);
  EXPECT_TRUE(panel.busy());
  EXPECT_TRUE(Child<QPushButton>(panel, "abort_button")->isEnabled());
  EXPECT_FALSE(Child<QPushButton>(panel, "calibrate_button")->isEnabled());
  AnswerPrompt(panel, QMessageBox::Yes);
  ASSERT_TRUE(WaitIdle(panel));
  const c::CommandOutcome& o = panel.last_outcome();
  ASSERT_EQ(o.exit_code, c::kExitOk) << o.text;

  // Every step shown and done; the bar full.
  auto* steps = Child<QListWidget>(panel, "steps_list");
  ASSERT_EQ(steps->count(), 7);
  const char* names[7] = {"current offset", "encoder direction", "range", "index", "friction", "gravity", "save"};
  for (int i = 0; i < 7; ++i) EXPECT_EQ(steps->item(i)->text().toStdString(), std::string("✓  ") + names[i]);
  EXPECT_EQ(Child<QProgressBar>(panel, "step_progress")->value(), 1000);
  EXPECT_EQ(Child<QLabel>(panel, "step_label")->text().toStdString(), "done");
  EXPECT_EQ(Child<QLabel>(panel, "result_label")->text().toStdString().rfind("PASS: calibration saved in slot A", 0),
            0u);
  EXPECT_FALSE(Child<QPushButton>(panel, "abort_button")->isEnabled());

  // The recovered values are the arm's ground truth (as tests/calibrate's ground-truth test).
  const nlohmann::json& r = o.json;
  const emu::ArmGroundTruth t = emu::RandomArm(kSeed);
  const double park[3] = {0.0, 0.0, static_cast<double>(0.135f)};
  for (int j = 0; j < 3; ++j) {
    const auto& m = r["measured"]["joints"][kJoint[j]];
    const double count = t.count(j);
    const int direction = m["direction"].get<int>();
    EXPECT_EQ(direction, t.plant.encoder[j].direction) << kJoint[j];
    const double true_offset = t.power_up[emu::JointOfMotor(j)] - direction * park[j] + 0.5 * count;
    EXPECT_LE(std::abs(m["position_offset"].get<double>() - true_offset), 2 * count) << kJoint[j];
    EXPECT_LE(std::abs(m["index_position"].get<double>() - t.reference_index(j)), 2 * count) << kJoint[j];
    const double range_tol = j < 2 ? 0.5 * kDeg : 0.5e-3;
    EXPECT_NEAR(m["lower_stop"].get<double>(), t.lower_stop(j), range_tol) << kJoint[j];
    EXPECT_NEAR(m["upper_stop"].get<double>(), t.upper_stop(j), range_tol) << kJoint[j];
    const double kt = t.torque_constant_ratio(
        j, fp::find_parameter(static_cast<std::uint16_t>(fp::param::kTorqueConstant + j))->default_value);
    EXPECT_NEAR(m["coulomb"].get<double>(), t.coulomb(j) / kt, 0.10 * t.coulomb(j) / kt) << kJoint[j];
    EXPECT_NEAR(m["viscous"].get<double>(), t.viscous(j) / kt, 0.10 * t.viscous(j) / kt) << kJoint[j];
  }
  const double kt = t.torque_constant_ratio(1, fp::find_parameter(fp::param::kTorqueConstant + 1)->default_value);
  const double gs = -t.plant.pitch_gravity_sin_Nm / kt, gc = -t.plant.pitch_gravity_cos_Nm / kt;
  const double rs = r["measured"]["gravity"]["sin"].get<double>(), rc = r["measured"]["gravity"]["cos"].get<double>();
  double worst = 0.0;
  for (double a = t.lower_stop(1); a <= t.upper_stop(1); a += 0.01)
    worst = std::max(worst, std::abs(rs * std::sin(a) + rc * std::cos(a) - (gs * std::sin(a) + gc * std::cos(a))));
  EXPECT_LE(worst, 0.10 * std::hypot(gs, gc));

  // The table: one row per check, in the report's order, each passed.
  auto* table = Child<QTableWidget>(panel, "results_table");
  ASSERT_EQ(table->rowCount(), static_cast<int>(r["checks"].size()));
  EXPECT_EQ(table->rowCount(), 28);
  for (int row = 0; row < table->rowCount(); ++row) {
    const auto& check = r["checks"][static_cast<std::size_t>(row)];
    EXPECT_EQ(table->item(row, 0)->text().toStdString(), check["name"].get<std::string>());
    EXPECT_EQ(table->item(row, 3)->text().toStdString(), "pass") << check.dump();
    EXPECT_FALSE(table->item(row, 2)->text().isEmpty());
  }

  // The report and its files, where the Open report button points.
  auto* open_report = Child<QPushButton>(panel, "open_report_button");
  EXPECT_TRUE(open_report->isEnabled());
  const std::filesystem::path html = panel.report_html();
  EXPECT_EQ(html.filename(), "arm1-calibrate.html");
  const std::filesystem::path session = r["session_dir"].get<std::string>();
  EXPECT_EQ(html.parent_path(), session);
  for (const char* key : {"report_html", "report_json", "friction_png", "range_png", "image_stored"})
    EXPECT_TRUE(std::filesystem::is_regular_file(session / r["files"][key].get<std::string>())) << key;
  EXPECT_TRUE(std::filesystem::is_regular_file(session / "bus.log"));
  std::ifstream page(html);
  const std::string text((std::istreambuf_iterator<char>(page)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("yaw.coulomb"), std::string::npos);

  // docs/images/calibration-panel.png is this moment (VESICA_CALIBRATION_PANEL_PNG=path).
  if (const char* png = std::getenv("VESICA_CALIBRATION_PANEL_PNG")) {
    QTest::qWait(200);
    EXPECT_TRUE(panel.grab().save(png)) << png;
  }

  // The node booted what was saved.
  c::ToolSession* s = panel.last_session();
  ASSERT_NE(s, nullptr);
  emu::ArmEmulator* arm = s->bus().emulated_arm(1);
  ASSERT_NE(arm, nullptr);
  EXPECT_EQ(arm->node().active_slot(), 0);
  EXPECT_FLOAT_EQ(arm->node().parameters().f32(fp::param::kCoulombFriction + 0),
                  static_cast<float>(r["measured"]["joints"]["yaw"]["coulomb"].get<double>()));
  std::filesystem::remove_all(dir);
}

TEST(CalibrationPanel, AbortMidStepLeavesTheArmDisabledOnItsStoredCalibration) {
  constexpr std::uint64_t kSeed = 5;
  const std::string dir = FreshDir("abort");
  {  // A calibration stored before (by the library, as vesica-calibrate would).
    c::SilentUi quiet;
    c::ToolOptions first = Emulated(kSeed, dir);
    first.command = "calibrate";
    c::ToolSession session(first, quiet, nullptr);
    ASSERT_EQ(c::Calibrate(session, 1, c::CalibrateRequest{}).exit_code, c::kExitOk);
  }
  CalibrationPanel panel(Emulated(kSeed, dir));
  panel.show();
  ASSERT_TRUE(WaitIdle(panel));  // the scan
  // The arm as stored, before the panel's calibration opens its session.
  ASSERT_NE(panel.last_session(), nullptr);
  emu::ArmEmulator* before = panel.last_session()->bus().emulated_arm(1);
  ASSERT_NE(before, nullptr);
  const std::vector<std::uint8_t> flash = before->board().flash().bytes();
  const float coulomb = before->node().parameters().f32(fp::param::kCoulombFriction + 1);
  ASSERT_EQ(before->node().active_slot(), 0);
  ASSERT_NE(coulomb, 0.0f);

  QTest::mouseClick(Child<QPushButton>(panel, "calibrate_button"), Qt::LeftButton);
  AnswerPrompt(panel, QMessageBox::Yes);
  // Abort once the friction sweeps are under way.
  auto* label = Child<QLabel>(panel, "step_label");
  ASSERT_TRUE(QTest::qWaitFor([&] { return label->text().contains("friction"); }, kCommandTimeoutMs))
      << label->text().toStdString();
  QTest::mouseClick(Child<QPushButton>(panel, "abort_button"), Qt::LeftButton);
  ASSERT_TRUE(WaitIdle(panel));

  const c::CommandOutcome& o = panel.last_outcome();
  EXPECT_EQ(o.exit_code, c::kExitAborted) << o.text;
  EXPECT_EQ(o.json["error"]["step"], "friction");
  EXPECT_EQ(o.json["error"]["reason"], "abort_requested");
  EXPECT_EQ(Child<QLabel>(panel, "step_label")->text().toStdString(), "stopped: aborted");
  EXPECT_NE(Child<QLabel>(panel, "result_label")->text().toStdString().find("the stored calibration is in force"),
            std::string::npos);
  EXPECT_FALSE(Child<QPushButton>(panel, "open_report_button")->isEnabled());
  EXPECT_EQ(Child<QTableWidget>(panel, "results_table")->rowCount(), 0);
  EXPECT_TRUE(panel.report_html().empty());
  EXPECT_NE(Child<QPlainTextEdit>(panel, "log")->toPlainText().toStdString().find("Abort pressed"), std::string::npos);

  // A few bus periods for the node to take the abort frame, then: disabled, no current, the
  // stored calibration in force, nothing written.
  c::ToolSession* s = panel.last_session();
  ASSERT_NE(s, nullptr);
  emu::ArmEmulator* arm = s->bus().emulated_arm(1);
  ASSERT_NE(arm, nullptr);
  std::string error;
  device::calibration::CalibrationLink* link = s->LinkTo(1, &error);
  ASSERT_NE(link, nullptr) << error;
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
  std::filesystem::remove_all(dir);
}

TEST(CalibrationPanel, NoToTheMotionPromptMovesNothing) {
  const std::string dir = FreshDir("declined");
  CalibrationPanel panel(Emulated(9, dir));
  ASSERT_TRUE(WaitIdle(panel));
  QTest::mouseClick(Child<QPushButton>(panel, "calibrate_button"), Qt::LeftButton);
  AnswerPrompt(panel, QMessageBox::No);
  ASSERT_TRUE(WaitIdle(panel));
  EXPECT_EQ(panel.last_outcome().exit_code, c::kExitAborted);
  EXPECT_NE(panel.last_outcome().text.find("not confirmed; nothing moved"), std::string::npos)
      << panel.last_outcome().text;
  emu::ArmEmulator* arm = panel.last_session()->bus().emulated_arm(1);
  ASSERT_NE(arm, nullptr);
  EXPECT_FALSE(arm->node().calibration_session_open());
  EXPECT_EQ(arm->node().active_slot(), -1);
  std::filesystem::remove_all(dir);
}

// The trainer at an arm station: Tools > Calibrate arms takes the arms from the session (its bridge
// lets go of vesica-armsim's ports, so the panel can bind them), scans both over UDP, and gives
// them back to the session when it closes.
TEST(CalibrationPanel, TheTrainerHandsItsArmsToThePanelAndTakesThemBack) {
  const int base = device::testing::FreeArmBasePort();
  ASSERT_NE(base, 0);
  device::testing::ArmsimProcess left, right;
  ASSERT_TRUE(left.Start(VESICA_ARMSIM_PATH, {"--node-id", "1", "--local-port", std::to_string(base), "--random-arm",
                                              "3", "--log-level", "warn"}));
  ASSERT_TRUE(right.Start(VESICA_ARMSIM_PATH,
                          {"--node-id", "2", "--local-port", std::to_string(base + 2), "--log-level", "warn"}));
  const std::string dir = FreshDir("trainer");
  ::setenv("VESICA_CALIBRATION_DIR", dir.c_str(), 1);  // the trainer's panel uses the tool's default folder

  const Scenario scenario =
      LoadScenario(std::filesystem::path(VESICA_SOURCE_DIR) / "data/scenarios/cholecystectomy-arms.toml");
  const SceneMeshes meshes = LoadSceneMeshes(scenario);
  TrainerOptions options;
  options.arms_udp_base_port = base;
  TrainerWindow w(scenario, std::make_unique<LaparoscopeView>(scenario, meshes),
                  BuildDissectionModelFor(scenario, meshes), options);
  w.show();
  ASSERT_FALSE(w.ArmStatusLines().empty()) << w.last_error();

  QAction* calibrate = w.menuBar()->findChild<QAction*>("calibrate_arms");
  ASSERT_NE(calibrate, nullptr);
  calibrate->trigger();
  auto* panel = w.findChild<QDialog*>("calibration_panel");
  ASSERT_NE(panel, nullptr);
  EXPECT_TRUE(panel->isModal());
  EXPECT_TRUE(w.ArmStatusLines().empty()) << "the session still holds the arms";
  EXPECT_EQ(Child<QLabel>(*panel, "bus_label")->text().toStdString(), "Bus: UDP 127.0.0.1:" + std::to_string(base));
  auto* scan = Child<QPushButton>(*panel, "scan_button");
  auto* view = Child<QPlainTextEdit>(*panel, "arms_view");
  // The arms boot within a moment: scan until both answer.
  const auto both = [&] {
    const std::string text = view->toPlainText().toStdString();
    return text.find("arm 1 (node 1, serial 0x5E51CA01)") != std::string::npos &&
           text.find("arm 2 (node 2, serial 0x5E51CA01)") != std::string::npos;
  };
  for (int attempt = 0; attempt < 10 && !both(); ++attempt) {
    ASSERT_TRUE(QTest::qWaitFor([&] { return scan->isEnabled(); }, kCommandTimeoutMs));
    if (!both()) QTest::mouseClick(scan, Qt::LeftButton);
  }
  EXPECT_TRUE(both()) << view->toPlainText().toStdString();
  ASSERT_TRUE(QTest::qWaitFor([&] { return scan->isEnabled(); }, kCommandTimeoutMs));

  QTest::mouseClick(Child<QPushButton>(*panel, "close_button"), Qt::LeftButton);
  EXPECT_FALSE(w.ArmStatusLines().empty()) << "the arms did not come back: " << w.last_error();
  EXPECT_TRUE(QTest::qWaitFor([&] { return w.findChild<QDialog*>("calibration_panel") == nullptr; }, 5000));
  left.Kill(SIGTERM);
  right.Kill(SIGTERM);
  std::string ignored;
  left.Finish(&ignored);
  right.Finish(&ignored);
  ::unsetenv("VESICA_CALIBRATION_DIR");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace vesica::app
