#include "app/needle_mode/needle_window.h"

#include <QVTKOpenGLNativeWidget.h>
#include <spdlog/spdlog.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkRenderer.h>

#include <QApplication>
#include <QCheckBox>
#include <QCloseEvent>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QKeyEvent>
#include <QLabel>
#include <QMenuBar>
#include <QSplitter>
#include <QStatusBar>
#include <QTimer>
#include <QVBoxLayout>
#include <chrono>

#include "app/history/metrics_panel.h"
#include "app/needle_mode/breathing_panel.h"
#include "app/needle_mode/ct_slice_widget.h"
#include "app/needle_mode/patient_view.h"
#include "app/records/pending_sessions.h"
#include "app/session/session_recording_file.h"
#include "device/stylus/keyboard_stylus.h"

namespace vesica::app::needle_mode {
namespace {

std::int64_t NowUnix() {
  return std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}

QString Text(const std::string& s) { return QString::fromStdString(s); }

}  // namespace

NeedleWindow::NeedleWindow(std::shared_ptr<const biopsy::BiopsyPatient> patient,
                           std::vector<patient::OrganSurface> surfaces, std::shared_ptr<device::StylusDevice> stylus,
                           std::function<void()> servo, const NeedleModeOptions& options)
    : patient_(std::move(patient)),
      stylus_(std::move(stylus)),
      servo_(std::move(servo)),
      options_(options),
      slice_ct_(patient_->ct) {
  setWindowTitle(QString::fromUtf8("Vesica — needle biopsy (") + Text(options_.trainee_id) + ")");
  view_ = std::make_unique<PatientView>(*patient_, std::move(surfaces));
  vtk_widget_ = new QVTKOpenGLNativeWidget(this);
  auto window = vtkSmartPointer<vtkGenericOpenGLRenderWindow>::New();
  vtk_widget_->setRenderWindow(window);
  window->AddRenderer(view_->renderer());
  vtk_widget_->setObjectName("patient_view");

  axial_ = new CtSliceWidget("Axial CT through the needle tip", this);
  axial_->setObjectName("axial_slice");
  oblique_ = new CtSliceWidget("Oblique CT in the needle's plane", this);
  oblique_->setObjectName("oblique_slice");
  breathing_ = new BreathingPanel(
      physics::RespirationSettings{}, [this](const physics::RespirationSettings& s) { runner_->SetRespiration(s); },
      [this](bool hold) {
        if (hold) {
          runner_->HoldBreath();
        } else {
          runner_->ResumeBreathing();
        }
      },
      this);
  show_tumour_ = new QCheckBox("Show the tumour in 3D (T)", this);
  show_tumour_->setObjectName("show_tumour");
  show_tumour_->setChecked(false);
  connect(show_tumour_, &QCheckBox::toggled, this, [this](bool on) {
    view_->SetTumourVisible(on);
    vtk_widget_->renderWindow()->Render();
  });
  metrics_ = new MetricsPanel(this);
  metrics_->setObjectName("biopsy_metrics");
  metrics_->Show(SessionMetrics{}, Procedure::kNeedleBiopsy);
  metrics_->setVisible(false);
  task_label_ = new QLabel(this);
  task_label_->setObjectName("task_label");
  task_label_->setWordWrap(true);

  auto* breathing_box = new QGroupBox("Breathing", this);
  auto* breathing_layout = new QVBoxLayout(breathing_box);
  breathing_layout->addWidget(breathing_);
  auto* slices = new QHBoxLayout;
  slices->addWidget(axial_, 1);
  slices->addWidget(oblique_, 1);
  auto* controls = new QVBoxLayout;
  controls->addWidget(breathing_box);
  controls->addWidget(show_tumour_);
  controls->addWidget(task_label_);
  controls->addStretch(1);
  auto* lower = new QHBoxLayout;
  lower->addLayout(controls, 1);
  lower->addWidget(metrics_, 1);
  auto* side = new QWidget(this);
  auto* side_layout = new QVBoxLayout(side);
  side_layout->addLayout(slices, 3);
  side_layout->addLayout(lower, 2);
  auto* split = new QSplitter(Qt::Horizontal, this);
  split->addWidget(vtk_widget_);
  split->addWidget(side);
  split->setStretchFactor(0, 1);
  split->setStretchFactor(1, 1);
  split->setSizes({520, 680});
  setCentralWidget(split);
  view_->SetTumourVisible(false);

  device_label_ = new QLabel(this);
  device_label_->setObjectName("device_status");
  statusBar()->addPermanentWidget(device_label_);

  QMenu* session = menuBar()->addMenu("&Session");
  session->addAction("&Reset (R)", [this] { ResetSession(); });
  session->addAction("&End session (Enter)", [this] { Finish(true); });
  QMenu* procedure = session->addMenu("&Procedure");
  procedure
      ->addAction("&Laparoscopic cholecystectomy",
                  [this] {
                    if (!switch_back_) return;
                    EndAndStoreSession();
                    QTimer::singleShot(0, this, switch_back_);
                  })
      ->setObjectName("procedure_cholecystectomy");
  QAction* biopsy = procedure->addAction("&Needle biopsy");
  biopsy->setCheckable(true);
  biopsy->setChecked(true);
  biopsy->setEnabled(false);
  session->addSeparator();
  session->addAction("&Quit", [this] { close(); });

  if (!options_.records_location.empty()) {
    saver_ = std::make_unique<SessionSaver>(options_.records_location, PendingSessionsPath(options_.records_location),
                                            options_.saver);
  }
  qApp->installEventFilter(this);
  StartRunner();
  timer_ = new QTimer(this);
  connect(timer_, &QTimer::timeout, this, [this] { Tick(); });
  timer_->start(33);  // 30 Hz: the seed drew at 20 Hz
  if (dynamic_cast<device::KeyboardStylus*>(stylus_.get()) != nullptr) {
    statusBar()->showMessage(QString::fromLatin1(device::KeyboardStylusHelp()) + "   Space: biopsy   H: hold breath");
  }
}

NeedleWindow::~NeedleWindow() {
  qApp->removeEventFilter(this);
  if (runner_) runner_->Stop();
  if (saver_) saver_->Finish(true);
}

void NeedleWindow::SetProcedureSwitcher(std::function<void()> switch_back) { switch_back_ = std::move(switch_back); }

void NeedleWindow::StartRunner() {
  if (runner_) runner_->Stop();
  biopsy::BiopsySessionSettings settings;
  settings.respiration = breathing_->settings();
  settings.needle.max_force_N = stylus_->Capabilities().max_force_N;
  settings.liver_motion = options_.liver_motion;
  runner_ = std::make_unique<biopsy::BiopsyRunner>(patient_, stylus_, settings, 0.001, servo_);
  if (breathing_->holding()) runner_->HoldBreath();
  started_unix_s_ = NowUnix();
  finished_shown_ = false;
  needle_moved_ = false;
  next_slice_s_ = 0.0;
  metrics_->setVisible(false);
  task_label_->setText("Find the tumour on the CT, enter between the ribs, and take the biopsy with button 1 (Space).");
}

void NeedleWindow::ResetSession() {
  if (!finished_shown_ && needle_moved_) Finish(true);
  StartRunner();
}

void NeedleWindow::Tick() {
  TakeSaveResults();
  const biopsy::NeedleFrame needle = runner_->LatestNeedle();
  const physics::PatientSnapshot& patient = runner_->LatestPatient();
  if (needle.inside) needle_moved_ = true;
  view_->Update(patient, needle);
  if (needle.time_s >= next_slice_s_) {
    UpdateSlices(patient, needle);
    next_slice_s_ = needle.time_s + options_.slice_period_s;
  }
  vtk_widget_->renderWindow()->Render();

  const bool ok = stylus_->Status() == device::DeviceStatus::kOk;
  device_label_->setText(Text(stylus_->StatusText()));
  device_label_->setStyleSheet(ok ? "" : "color: #d03030; font-weight: bold");
  if (const std::string error = runner_->error(); !error.empty() && last_error_ != error) {
    last_error_ = error;
    statusBar()->showMessage(QStringLiteral("Needle stopped: ") + Text(error));
  }
  if (!finished_shown_) {
    task_label_->setText(QStringLiteral("Time %1 s   attempts %2   no-go crossings %3   %4")
                             .arg(needle.time_s, 0, 'f', 1)
                             .arg(needle.insertion_attempts)
                             .arg(needle.nogo_crossings)
                             .arg(needle.inside
                                      ? QStringLiteral("needle %1 mm in").arg(needle.inserted_m * 1e3, 0, 'f', 0)
                                      : QStringLiteral("needle outside")));
    if (needle.finished) Finish(false);
  }
}

void NeedleWindow::UpdateSlices(const physics::PatientSnapshot& patient, const biopsy::NeedleFrame& needle) {
  slice_ct_.SetPatient(patient);
  slice_ct_.SetBlend(1.0);
  const std::optional<Eigen::Vector3d> tumour =
      show_tumour_->isChecked() ? std::optional<Eigen::Vector3d>(slice_ct_.TumourCentre_m()) : std::nullopt;
  const biopsy::SlicePlane axial = biopsy::AxialSliceThrough(needle.pose.tip_m);
  axial_->Show(axial, biopsy::SampleSlice(slice_ct_, axial), needle.pose, tumour);
  const biopsy::SlicePlane oblique = biopsy::ObliqueSliceAlong(needle.pose);
  oblique_->Show(oblique, biopsy::SampleSlice(slice_ct_, oblique), needle.pose, tumour);
}

void NeedleWindow::Finish(bool unfinished) {
  if (finished_shown_) return;
  finished_shown_ = true;
  const SessionMetrics metrics = runner_->Metrics();
  metrics_->Show(metrics, Procedure::kNeedleBiopsy);
  metrics_->setVisible(true);
  task_label_->setText(unfinished ? QStringLiteral("Session ended without a biopsy. R starts a new one.")
                                  : QStringLiteral("Biopsy taken. Withdraw the needle; R starts a new one."));
  if (!saver_) return;
  SessionRecord record;
  record.trainee_id = options_.trainee_id;
  record.scenario = "Liver biopsy (synthetic patient)";
  record.station = options_.station;
  record.procedure = Procedure::kNeedleBiopsy;
  record.started_unix_s = started_unix_s_;
  record.ended_unix_s = std::max(started_unix_s_, NowUnix());
  record.unfinished = unfinished;
  record.metrics = metrics;
  // The stylus stream is a bonus: when it cannot be written the session is stored without it.
  if (!options_.recordings_dir.empty()) {
    std::filesystem::path path;
    try {
      const device::StylusRecording stream = runner_->Recording();
      if (!stream.samples.empty()) {
        path = CreateSessionRecordingFile(options_.recordings_dir, options_.trainee_id + "-biopsy", started_unix_s_);
        device::WriteStylusRecording(path, stream);
        record.input_recording_path = path.string();
      }
    } catch (const std::exception& e) {
      std::error_code ignored;
      if (!path.empty()) std::filesystem::remove(path, ignored);
      spdlog::warn("biopsy of {}: stylus recording not saved: {}", options_.trainee_id, e.what());
    }
  }
  save_ticket_ = saver_->Save(record);
}

void NeedleWindow::EndAndStoreSession() {
  if (!finished_shown_ && needle_moved_) Finish(true);
  if (runner_) runner_->Stop();
  if (saver_) {
    saver_->Finish(true);
    TakeSaveResults();
  }
}

void NeedleWindow::TakeSaveResults() {
  if (!saver_) return;
  for (const SaveResult& result : saver_->TakeResults()) {
    if (result.ticket == save_ticket_ && result.id) stored_id_ = result.id;
    statusBar()->showMessage(Text(result.message));
    if (result.kept_pending) last_error_ = result.message;
  }
}

bool NeedleWindow::eventFilter(QObject* watched, QEvent* event) {
  // Keys meant for this window or a widget in it (the application-wide filter sees them first, so
  // that the VTK view does not swallow the stylus' keys).
  const auto* target = qobject_cast<QWidget*>(watched);
  if (target == nullptr || target->window() != this ||
      (event->type() != QEvent::KeyPress && event->type() != QEvent::KeyRelease))
    return QMainWindow::eventFilter(watched, event);
  auto* key = static_cast<QKeyEvent*>(event);
  if (key->isAutoRepeat() && key->key() == Qt::Key_Space) return true;
  auto* keyboard = dynamic_cast<device::KeyboardStylus*>(stylus_.get());
  if (key->key() == Qt::Key_Space && keyboard != nullptr) {
    keyboard->SetButton(1, event->type() == QEvent::KeyPress);
    return true;
  }
  if (event->type() != QEvent::KeyPress) return QMainWindow::eventFilter(watched, event);
  switch (key->key()) {
    case Qt::Key_H:
      breathing_->SetHolding(!breathing_->holding());
      return true;
    case Qt::Key_T:
      show_tumour_->setChecked(!show_tumour_->isChecked());
      return true;
    case Qt::Key_R:
      ResetSession();
      return true;
    case Qt::Key_Return:
    case Qt::Key_Enter:
      Finish(true);
      return true;
    default:
      break;
  }
  if (keyboard != nullptr && !key->text().isEmpty() && keyboard->ApplyKey(key->text().at(0).toLatin1())) return true;
  return QMainWindow::eventFilter(watched, event);
}

void NeedleWindow::closeEvent(QCloseEvent* event) {
  EndAndStoreSession();
  event->accept();
}

}  // namespace vesica::app::needle_mode
