#include "app/trainer/trainer_window.h"

#include <QVTKOpenGLNativeWidget.h>
#include <vtkCamera.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkRenderer.h>

#include <spdlog/spdlog.h>

#include <QAction>
#include <QCloseEvent>
#include <QDockWidget>
#include <QFileDialog>
#include <QKeyEvent>
#include <QLabel>
#include <QMenuBar>
#include <QMouseEvent>
#include <QPushButton>
#include <QStatusBar>
#include <QTimer>
#include <QWheelEvent>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <thread>

#include "app/calot/debrief_screen.h"
#include "app/history/history_window.h"
#include "app/history/metrics_panel.h"
#include "app/records/pending_sessions.h"
#include "app/records/session_store.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/arm_bridge.h"
#include "app/session/arm_input.h"
#include "app/session/arms_standing_by.h"
#include "app/session/dissection_setup.h"
#include "app/session/session_recording_file.h"
#include "app/trainer/calibration_panel.h"
#include "app/trainer/keyboard_control.h"
#include "device/input/input_recording.h"
#include "device/input/replay_input.h"

namespace vesica::app {

namespace {
std::int64_t UnixNow() {
  return std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}

QString Rate(const char* name, const LoopRate& r) {
  return QString::asprintf("%-8s %7.1f Hz  jitter %.2f ms  worst %.1f ms", name, r.rate_hz, r.jitter_ms, r.worst_ms);
}
}  // namespace

TrainerWindow::TrainerWindow(const Scenario& scenario, std::unique_ptr<LaparoscopeView> view,
                             std::shared_ptr<const physics::DissectionModel> model, const TrainerOptions& options)
    : scenario_(scenario), options_(options), view_(std::move(view)) {
  setWindowTitle(QString::fromStdString("Vesica — " + scenario.name + " — " + options.trainee_id));
  vtk_widget_ = new QVTKOpenGLNativeWidget(this);
  auto window = vtkSmartPointer<vtkGenericOpenGLRenderWindow>::New();
  window->SetMultiSamples(0);  // keeps translucent membranes and smoke visible on Mesa
  window->AddRenderer(view_->renderer());
  vtk_widget_->setRenderWindow(window);
  setCentralWidget(vtk_widget_);
  for (const auto& instrument : scenario.instruments) max_insertion_m_.push_back(instrument.shaft_length_m);
  vtk_widget_->installEventFilter(this);
  vtk_widget_->setFocus();

  diagnostics_ = new QLabel(vtk_widget_);
  diagnostics_->setObjectName("diagnostics");
  diagnostics_->setStyleSheet(
      "QLabel { color: #e8e8e8; background: rgba(0,0,0,140); font-family: monospace; padding: 4px; }");
  diagnostics_->move(8, 8);

  metrics_panel_ = new MetricsPanel(this);
  auto* dock = new QDockWidget("Session metrics", this);
  dock->setObjectName("metrics_dock");
  dock->setWidget(metrics_panel_);
  addDockWidget(Qt::RightDockWidgetArea, dock);
  dock->hide();
  if (scenario.calot_triangle) {
    calot_debrief_ = new calot::DebriefScreen(this);
    auto* debrief_dock = new QDockWidget("Calot's triangle: debrief", this);
    debrief_dock->setObjectName("calot_debrief_dock");
    debrief_dock->setWidget(calot_debrief_);
    // A tab beside the metrics, raised when the case ends: the view keeps its width.
    addDockWidget(Qt::RightDockWidgetArea, debrief_dock);
    tabifyDockWidget(dock, debrief_dock);
    debrief_dock->hide();
    connect(calot_debrief_->CloseButton(), &QPushButton::clicked, debrief_dock, &QDockWidget::hide);
  }

  QMenu* session = menuBar()->addMenu("&Session");
  session->addAction("&Pause / resume (P)", [this] { runner_->SetPaused(!runner_->Status().paused); });
  session->addAction("&Reset (R)", [this] { ResetSession(); });
  session->addAction("&End session (Enter)", [this] { EndSession(); });
  QAction* exchange = session->addAction("E&xchange the right hand's instrument (T)", [this] { ExchangeRightTool(); });
  exchange->setObjectName("exchange_right_tool");
  exchange->setEnabled(RightPortExchange(scenario).tools().size() > 1);
  open_scenario_action_ = session->addAction("Open &scenario...", [this] {
    const QString file = QFileDialog::getOpenFileName(
        this, "Open a scenario", QString::fromStdString(DefaultScenarioPath().parent_path().string()),
        "Vesica scenarios (*.toml);;All files (*)");
    if (!file.isEmpty()) RequestScenario(file.toStdString());
  });
  open_scenario_action_->setObjectName("open_scenario");
  open_scenario_action_->setEnabled(false);
  QMenu* procedure = session->addMenu("P&rocedure");
  QAction* cholecystectomy = procedure->addAction("&Laparoscopic cholecystectomy");
  cholecystectomy->setCheckable(true);
  cholecystectomy->setChecked(true);
  cholecystectomy->setEnabled(false);
  needle_biopsy_action_ = procedure->addAction("&Needle biopsy", [this] { RequestNeedleBiopsy(); });
  needle_biopsy_action_->setObjectName("procedure_needle_biopsy");
  needle_biopsy_action_->setEnabled(false);
  QAction* clear_faults = session->addAction("&Clear arm faults", [this] {
    if (arms_) arms_->ResetFaults();
  });
  clear_faults->setShortcut(QKeySequence(QStringLiteral("Ctrl+F")));
  session->addSeparator();
  QAction* quit = session->addAction("&Quit", [this] { close(); });
  quit->setObjectName("quit");
  quit->setShortcut(QKeySequence::Quit);  // Ctrl+Q
  quit->setShortcutContext(Qt::ApplicationShortcut);
  QMenu* view_menu = menuBar()->addMenu("&View");
  view_menu->addAction("&Diagnostics overlay (F2)", [this] { diagnostics_->setVisible(!diagnostics_->isVisible()); });
  menuBar()->addAction("&History...", [this] { OpenHistory(); });
  QMenu* tools = menuBar()->addMenu("&Tools");
  tools->addAction("&Calibrate arms...", [this] { OpenCalibration(); })->setObjectName("calibrate_arms");

  // The session's input: --replay, else what the scenario names (a replay file, haptic arms),
  // else the keyboard; Session > Input switches while running.
  model_ = std::move(model);
  poses_ = initial_poses_ = view_->poses();
  right_port_ = RightPortExchange(scenario_);
  if (!options.records_location.empty())
    saver_ = std::make_unique<SessionSaver>(options.records_location, PendingSessionsPath(options.records_location),
                                            options.saver);
  saving_label_ = new QLabel("saving...", this);
  saving_label_->setObjectName("saving");
  saving_label_->hide();
  statusBar()->addPermanentWidget(saving_label_);
  lag_label_ = new QLabel(this);
  lag_label_->setObjectName("physics_lag");
  lag_label_->hide();
  statusBar()->addPermanentWidget(lag_label_);
  std::filesystem::path replay = options.replay_file;
  for (const InstrumentConfig& c : scenario.instruments)
    if (replay.empty() && c.input == InputKind::kReplay && !c.replay_file.empty()) replay = c.replay_file;
  if (!replay.empty())
    StartSession(InputChoice::kReplay, replay);
  else
    StartSession(ArmBridge::ScenarioUsesArms(scenario) ? InputChoice::kArms : InputChoice::kKeyboard, {});
  QMenu* input_menu = session->addMenu("&Input");
  input_menu->addAction("&Keyboard", [this] { StartSession(InputChoice::kKeyboard, {}); });
  input_menu->addAction("&Replay a recording...", [this] {
    const QString file = QFileDialog::getOpenFileName(this, "Replay a recorded session", QString(),
                                                      "Vesica recordings (*.csv);;All files (*)");
    if (!file.isEmpty()) StartSession(InputChoice::kReplay, file.toStdString());
  });
  input_menu->addAction("Haptic &arms (scenario's CAN / emulated arms)",
                        [this] { StartSession(InputChoice::kArms, {}); });

  timer_ = new QTimer(this);
  connect(timer_, &QTimer::timeout, this, [this] { Tick(); });
  timer_->start(16);
  setToolTip(QString::fromStdString(scenario.description));
  resize(1280, 720);
}

TrainerWindow::~TrainerWindow() = default;

bool TrainerWindow::StartSession(InputChoice choice, const std::filesystem::path& replay_file) {
  std::shared_ptr<device::InstrumentInputSource> input;
  RunnerOptions ro;
  ro.scenario_name = scenario_.name;
  ro.real_time = options_.real_time;
  // The laparoscope's picture is the window's 16:9 (what of the tubes the camera sees).
  ro.calot = CalotSessionSetupFor(scenario_);
  std::string what, fallback;
  device::InputFrame initial;
  for (size_t i = 0; i < 2 && i < poses_.size(); ++i) initial.instruments[i].pose = poses_[i];
  try {
    switch (choice) {
      case InputChoice::kReplay: {
        auto replay = std::make_shared<device::ReplayInput>(device::ReadInputRecording(replay_file));
        ro.end_after_s = replay->end_time_s();
        input = replay;
        what = "replaying " + replay_file.string();
        // At an arm station the arms stay connected while a recording is watched: their state
        // stays on screen and the next session can take them without binding their ports again.
        if (ArmBridge::ScenarioUsesArms(scenario_)) {
          try {
            if (!arms_) arms_ = OpenArms();
            ArmBridge* b = arms_.get();
            ro.haptic_io = std::make_shared<ArmsStandingBy>(b->devices(), [b] { b->Tick(); });
            what += " (haptic arms connected, not driving)";
          } catch (const std::exception& e) {
            what += std::string(" (haptic arms not connected: ") + e.what() + ")";
          }
        }
        break;
      }
      case InputChoice::kArms: {
        if (arms_) {  // the running bridge holds the arms' ports: release them before binding again
          runner_.reset();
          arms_.reset();
        }
        auto bridge = OpenArms();
        ArmBridge* b = bridge.get();
        auto arms = std::make_shared<ArmInput>(b->devices(), model_->instruments, initial, [b] { b->Tick(); },
                                               RightPortExchange(scenario_));
        ro.haptic_io = arms;
        input = arms;
        runner_.reset();  // its threads use the old bridge: stop them first
        arms_ = std::move(bridge);
        what = "haptic arms";
        break;
      }
      case InputChoice::kKeyboard:
        break;
    }
  } catch (const std::exception& e) {
    ShowError(e.what());
    if (runner_) return false;  // keep the running session
    // Never a silent fallback: the status line keeps saying why the arms are not driving.
    fallback = std::string("Haptic arms could not start: ") + e.what() + " -- keyboard meanwhile  |  ";
    choice = InputChoice::kKeyboard;
  }
  if (choice == InputChoice::kKeyboard) {
    live_input_ = std::make_shared<LiveInput>(initial);
    input = live_input_;
    what = KeyboardHelp();
  } else {
    live_input_.reset();
  }
  runner_ = std::make_unique<SessionRunner>(model_, DefaultCauteryParams(), input, ro);
  input_choice_ = choice;
  session_number_ = 0;
  if (choice == InputChoice::kKeyboard) arms_.reset();  // after the runner that used it is gone
  finished_shown_ = stored_ = false;
  stored_id_.reset();
  HideEndOfSessionDocks();
  started_unix_s_ = UnixNow();
  runner_->Start();
  statusBar()->showMessage(QString::fromStdString(
      fallback + what + "  |  P pause, R reset, Enter end, +/- zoom, arrows look around, Shift+drag pan, F2 diagnostics"));
  return true;
}

std::unique_ptr<ArmBridge> TrainerWindow::OpenArms() const {
  ArmBridgeOptions options;
  options.udp_base_port = options_.arms_udp_base_port;
  return std::make_unique<ArmBridge>(scenario_, options);
}

void TrainerWindow::EndSession() { runner_->End(); }

RunnerStatus TrainerWindow::EndAndWait() {
  runner_->End();
  // The physics thread ends the session within one step (5 ms of work); a stuck step must not
  // hang the window, so the wait is bounded and the session is stored as it stands.
  RunnerStatus s = runner_->Status();
  for (int i = 0; i < 1000 && !(s.finished && s.session == session_number_); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    s = runner_->Status();
  }
  return s;
}

void TrainerWindow::EndAndStoreSession() {
  if (!finished_shown_) OnFinished(EndAndWait());
  if (saver_) saver_->Finish(false);
  TakeSaveResults();
}

void TrainerWindow::StoreUnfinishedSession() {
  if (!finished_shown_) {
    const RunnerStatus s = EndAndWait();
    // A session nobody touched (the window opened and closed) is not a training session.
    const bool touched = s.metrics.path_length_left_m > 0 || s.metrics.path_length_right_m > 0 ||
                         s.metrics.cautery_on_s > 0;
    if (touched) {
      OnFinished(s, /*unfinished=*/true);
    } else {
      finished_shown_ = true;
    }
  }
  if (saver_) saver_->Finish(true);  // closing: a locked database gets one try, then the pending file
  TakeSaveResults();
}

bool TrainerWindow::saving() const { return saver_ && saver_->Busy(); }

void TrainerWindow::closeEvent(QCloseEvent* event) {
  StoreUnfinishedSession();
  event->accept();
}

void TrainerWindow::ResetSession() {
  // The instruments go back to the scenario's start with the tissue: set the live input before
  // the new session samples it.
  poses_ = initial_poses_;
  pedal_ = false;
  right_port_ = RightPortExchange(scenario_);
  drag_instrument_ = -1;
  if (live_input_) SendManualPoses();
  session_number_ = runner_->Reset();
  started_unix_s_ = UnixNow();
  finished_shown_ = stored_ = false;
  stored_id_.reset();
  HideEndOfSessionDocks();
}

void TrainerWindow::ExchangeRightTool() {
  if (!live_input_) return;  // a replay or the arms (their handle button) hold the tool
  right_port_.Next();
  SendManualPoses();
  std::string name = physics::ToolKey(right_port_.current());
  std::replace(name.begin(), name.end(), '_', ' ');
  statusBar()->showMessage(QString::fromStdString("Right hand: " + name));
}

void TrainerWindow::HideEndOfSessionDocks() {
  for (const char* name : {"metrics_dock", "calot_debrief_dock"})
    if (auto* dock = findChild<QDockWidget*>(name)) dock->hide();
}

void TrainerWindow::SetScenarioOpener(std::function<void(const std::filesystem::path&)> open) {
  open_scenario_ = std::move(open);
  open_scenario_action_->setEnabled(static_cast<bool>(open_scenario_));
}

void TrainerWindow::SetNeedleBiopsyOpener(std::function<void()> open) {
  open_needle_biopsy_ = std::move(open);
  needle_biopsy_action_->setEnabled(static_cast<bool>(open_needle_biopsy_));
}

bool TrainerWindow::RequestNeedleBiopsy() {
  if (!open_needle_biopsy_) return false;
  open_needle_biopsy_();
  return true;
}

bool TrainerWindow::RequestScenario(const std::filesystem::path& scenario_path) {
  if (!open_scenario_) return false;
  open_scenario_(scenario_path);
  return true;
}

void TrainerWindow::ShowError(const std::string& message) {
  last_error_ = message;
  statusBar()->showMessage(QString::fromStdString(message));
}

std::string TrainerWindow::ArmStatusLines() const { return arms_ ? arms_->StatusLines() : std::string(); }

std::string TrainerWindow::LoopRatesSummary() const {
  const RunnerStatus s = runner_->Status();
  return (Rate("physics", s.physics) + "\n" + Rate("haptic", s.haptic) + "\n" +
          Rate("render", render_stats_.Snapshot()))
      .toStdString();
}

void TrainerWindow::Tick() {
  render_stats_.Tick(LoopStats::Clock::now());
  RenderFrame frame = runner_->LatestFrame();
  if (arms_)
    for (const device::ArmReport& r : arms_->Reports()) frame.arm_status.push_back(r.text);
  view_->Update(frame);
  vtk_widget_->renderWindow()->Render();
  const RunnerStatus s = runner_->Status();
  if (diagnostics_->isVisible()) {
    QString text = QString::asprintf("session  %7.2f s%s\n", s.session_time_s, s.paused ? "  (paused)" : "");
    text += QString::fromStdString(LoopRatesSummary()) + "\n";
    text += QString::asprintf("force    grasper %.2f N  hook %.2f N\n", s.haptic_force_N[0].norm(),
                              s.haptic_force_N[1].norm());
    text += QString::asprintf("springs  %d of %d cut", s.metrics.springs_cut, s.metrics.springs_total);
    if (arms_) text += "\n" + QString::fromStdString(arms_->Describe());
    diagnostics_->setText(text);
    diagnostics_->adjustSize();
  }
  // A finished status of the session before a Reset() is not this one's.
  if (s.finished && !finished_shown_ && s.session == session_number_) OnFinished(s);
  TakeSaveResults();
  saving_label_->setVisible(saving());
  // Real time is the trainee's: when physics cannot keep up, say so rather than slow the clock.
  if (options_.real_time && s.physics_lag_s > 0.25 && !s.finished) {
    lag_label_->setText(QString::asprintf("physics behind real time by %.1f s", s.physics_lag_s));
    lag_label_->show();
  } else {
    lag_label_->hide();
  }
}

void TrainerWindow::TakeSaveResults() {
  if (!saver_) return;
  for (const SaveResult& r : saver_->TakeResults()) {
    if (r.id) {
      if (r.ticket == save_ticket_) {  // an earlier session's save is not this one's
        stored_id_ = r.id;
        stored_ = true;
      }
      statusBar()->showMessage(QString::fromStdString(r.message + recording_note_));
    } else {
      ShowError(r.message + recording_note_);
    }
  }
}

void TrainerWindow::OnFinished(const RunnerStatus& status, bool unfinished) {
  finished_shown_ = true;
  SessionRecord record;
  record.trainee_id = options_.trainee_id;
  record.scenario = scenario_.name;
  record.started_unix_s = started_unix_s_;
  record.ended_unix_s = std::max(started_unix_s_, UnixNow());
  record.metrics = status.metrics;
  // The session lasted what the trainee lived (wall clock, pauses excluded), however far the
  // simulation fell behind; the lag is kept beside it. A fast replay has only simulated time.
  if (options_.real_time) record.metrics.duration_s = std::max(status.wall_time_s, 0.0);
  record.physics_lag_s = options_.real_time ? status.physics_lag_s : 0.0;
  record.station = options_.station;
  record.replay = input_choice_ == InputChoice::kReplay;
  record.unfinished = unfinished;
  metrics_panel_->Show(record.metrics);
  if (auto* dock = findChild<QDockWidget*>("metrics_dock")) dock->show();
  // The Calot step's debrief when the case ended (the critical error or the trainee's End); not
  // when the trainer is closing over a running case.
  if (calot_debrief_ && status.calot_metrics && !unfinished) {
    calot_debrief_->Show(*status.calot_metrics);
    if (auto* dock = findChild<QDockWidget*>("calot_debrief_dock")) {
      dock->show();
      dock->raise();
    }
  }
  if (!status.error.empty()) last_error_ = "physics stopped: " + status.error;

  // The input recording is a bonus: when it cannot be written the session is stored without it.
  recording_note_.clear();
  if (!options_.recordings_dir.empty()) {
    const device::InputRecording rec = runner_->Recording();
    if (!rec.frames.empty()) {
      std::filesystem::path path;
      try {
        path = CreateSessionRecordingFile(options_.recordings_dir, options_.trainee_id, started_unix_s_);
        device::WriteInputRecording(path, rec);
        record.input_recording_path = path.string();
      } catch (const std::exception& e) {
        std::error_code ignored;
        if (!path.empty()) std::filesystem::remove(path, ignored);
        recording_note_ = std::string("; its input recording was not saved: ") + e.what();
        spdlog::warn("session of {}: input recording not saved: {}", options_.trainee_id, e.what());
      }
    }
  }
  const std::string what = unfinished        ? "Session stopped (stored as unfinished)"
                           : status.case_ended ? "Case ended: bile duct injury (see the debrief)"
                                               : "Session finished";
  if (!saver_) {
    statusBar()->showMessage(QString::fromStdString(what + " (not stored: no records database)" + recording_note_));
    return;
  }
  save_ticket_ = saver_->Save(record);
  statusBar()->showMessage(QString::fromStdString(what + "; saving..." + recording_note_));
  saving_label_->show();
}

void TrainerWindow::OpenHistory() {
  if (options_.records_location.empty()) return;
  try {
    auto* history = new HistoryWindow(OpenSessionStore(options_.records_location), this);
    history->setAttribute(Qt::WA_DeleteOnClose);
    history->setWindowFlag(Qt::Window);
    history->show();
  } catch (const std::exception& e) {
    ShowError(e.what());
  }
}

void TrainerWindow::OpenCalibration() {
  // The panel binds the arms' ports (or interface) itself: the session lets go of them first
  // (keyboard meanwhile) and takes them back when the panel closes.
  const bool had_arms = input_choice_ == InputChoice::kArms;
  if (arms_) StartSession(InputChoice::kKeyboard, {});
  CalibrationPanel* panel = nullptr;
  try {
    panel = CalibrationPanel::ForTrainer(scenario_, options_.arms_udp_base_port, this);
  } catch (const std::exception& e) {
    ShowError(e.what());
    if (had_arms) StartSession(InputChoice::kArms, {});
    return;
  }
  panel->setAttribute(Qt::WA_DeleteOnClose);
  connect(panel, &QDialog::finished, this, [this, had_arms] {
    if (had_arms) StartSession(InputChoice::kArms, {});
  });
  panel->open();  // window-modal: the session's input menu waits until the arms are back
}

bool TrainerWindow::eventFilter(QObject* watched, QEvent* event) {
  if (watched == vtk_widget_ && event->type() == QEvent::KeyPress) {
    auto* key = static_cast<QKeyEvent*>(event);
    vtkCamera* camera = view_->renderer()->GetActiveCamera();
    switch (key->key()) {
      case Qt::Key_P:
        runner_->SetPaused(!runner_->Status().paused);
        return true;
      case Qt::Key_R:
        ResetSession();
        return true;
      case Qt::Key_Return:
      case Qt::Key_Enter:
        EndSession();
        return true;
      case Qt::Key_F2:
        diagnostics_->setVisible(!diagnostics_->isVisible());
        return true;
      case Qt::Key_T:  // exchange the right hand's tool through its port
        if (!live_input_) break;
        ExchangeRightTool();
        return true;
      case Qt::Key_Plus:
      case Qt::Key_Equal:
        camera->Zoom(1.1);
        return true;
      case Qt::Key_Minus:
        camera->Zoom(1.0 / 1.1);
        return true;
      case Qt::Key_Left:
        camera->Azimuth(2.0);
        return true;
      case Qt::Key_Right:
        camera->Azimuth(-2.0);
        return true;
      case Qt::Key_Up:
        camera->Elevation(2.0);
        camera->OrthogonalizeViewUp();
        return true;
      case Qt::Key_Down:
        camera->Elevation(-2.0);
        camera->OrthogonalizeViewUp();
        return true;
      default:
        break;
    }
    const QString text = key->text();
    if (live_input_ && text.size() == 1 &&
        ApplyInstrumentKey(text.at(0).toLatin1(), poses_, max_insertion_m_, pedal_)) {
      SendManualPoses();
      return true;
    }
  }
  if (watched == vtk_widget_ && live_input_ && MouseEvent(event)) return true;
  return QMainWindow::eventFilter(watched, event);
}

bool TrainerWindow::MouseEvent(QEvent* event) {
  switch (event->type()) {
    case QEvent::MouseButtonPress: {
      // Left button: grasper, right: hook. With Shift, or the middle button, VTK pans the view.
      const auto* mouse = static_cast<QMouseEvent*>(event);
      if (drag_instrument_ >= 0) return true;  // a second button during a drag: ignored
      if ((mouse->modifiers() & Qt::ShiftModifier) ||
          (mouse->button() != Qt::LeftButton && mouse->button() != Qt::RightButton))
        return false;
      drag_instrument_ = mouse->button() == Qt::LeftButton ? 0 : 1;
      drag_x_ = mouse->pos().x();
      drag_y_ = mouse->pos().y();
      return true;
    }
    case QEvent::MouseMove: {
      if (drag_instrument_ < 0) return false;
      const auto* mouse = static_cast<QMouseEvent*>(event);
      ApplyInstrumentDrag(static_cast<std::size_t>(drag_instrument_), mouse->pos().x() - drag_x_,
                          mouse->pos().y() - drag_y_, poses_);
      drag_x_ = mouse->pos().x();
      drag_y_ = mouse->pos().y();
      SendManualPoses();
      return true;
    }
    case QEvent::MouseButtonRelease: {
      const auto* mouse = static_cast<QMouseEvent*>(event);
      if (drag_instrument_ < 0) return false;
      if (mouse->button() == (drag_instrument_ == 0 ? Qt::LeftButton : Qt::RightButton)) drag_instrument_ = -1;
      return true;
    }
    case QEvent::Wheel: {  // while dragging: insertion; otherwise VTK zooms
      if (drag_instrument_ < 0) return false;
      const auto* wheel = static_cast<QWheelEvent*>(event);
      ApplyInstrumentWheel(static_cast<std::size_t>(drag_instrument_), wheel->angleDelta().y() / 120.0, poses_,
                           max_insertion_m_);
      SendManualPoses();
      return true;
    }
    default:
      return false;
  }
}

void TrainerWindow::SendManualPoses() {
  for (int i = 0; i < 2 && i < static_cast<int>(poses_.size()); ++i) {
    device::InstrumentInput in;
    in.pose = poses_[static_cast<size_t>(i)];
    in.pedal = i == 1 && pedal_;
    live_input_->Set(i, in);
  }
  live_input_->SetRightTool(right_port_.current());
}

}  // namespace vesica::app
