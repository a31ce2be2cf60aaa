#include "app/trainer/calibration_panel.h"

#include <QComboBox>
#include <QDesktopServices>
#include <QFileInfo>
#include <QFontDatabase>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QListWidget>
#include <QMessageBox>
#include <QPlainTextEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QSplitter>
#include <QTableWidget>
#include <QUrl>
#include <QVBoxLayout>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include "app/calibrate/commands.h"
#include "app/calibrate/exit_codes.h"
#include "app/calibrate/terminal_ui.h"
#include "app/trainer/calibration_bus.h"
#include "app/trainer/calibration_panel_ui.h"

namespace vesica::app {

namespace c = calibrate;

struct CalibrationPanel::State {
  c::ToolOptions options;
  std::atomic<bool> abort{false};
  std::atomic<bool> running{false};
  std::thread worker;
  std::unique_ptr<CalibrationPanelUi> ui;
  // The worker's; read by the GUI thread only while no command runs.
  std::unique_ptr<c::ToolSession> session;
  c::CommandOutcome outcome;
  std::string command;
  std::string report_html;

  QLabel* bus_label = nullptr;
  QPlainTextEdit* arms_view = nullptr;
  QComboBox* arm_choice = nullptr;
  QComboBox* joint_choice = nullptr;
  QComboBox* step_choice = nullptr;
  QPushButton* scan_button = nullptr;
  QPushButton* info_button = nullptr;
  QPushButton* calibrate_button = nullptr;
  QPushButton* abort_button = nullptr;
  QListWidget* steps_list = nullptr;
  QGroupBox* hand_box = nullptr;  // a guided hand motion's prompt, live value and answers
  QLabel* hand_instruction = nullptr;
  QLabel* hand_live = nullptr;
  QPushButton* hand_accept = nullptr;
  QPushButton* hand_retry = nullptr;
  QLabel* step_label = nullptr;
  QProgressBar* step_progress = nullptr;
  QPlainTextEdit* log = nullptr;
  QTableWidget* results = nullptr;
  QLabel* result_label = nullptr;
  QPushButton* open_report = nullptr;
};

namespace {

QString Q(const std::string& s) { return QString::fromStdString(s); }

template <typename W>
W* Named(W* w, const char* name) {
  w->setObjectName(name);
  return w;
}

// The step list's rows: the calibration's steps and the save at the end.
std::vector<std::string> StepRows(const std::vector<c::Step>& steps) {
  std::vector<std::string> rows;
  for (c::Step s : steps) rows.emplace_back(c::InfoOf(s).name);
  rows.emplace_back("save");
  return rows;
}

QString Number(double v, const std::string& unit) {
  // Counts and directions are whole; the rest with four significant digits.
  if (v == std::round(v) && std::abs(v) < 1e6) return QString::number(static_cast<long long>(v)) + " " + Q(unit);
  return QString::number(v, 'g', 4) + " " + Q(unit);
}

}  // namespace

CalibrationPanel::CalibrationPanel(const c::ToolOptions& options, QWidget* parent)
    : QDialog(parent), s_(std::make_unique<State>()) {
  s_->options = options;
  setObjectName("calibration_panel");
  setWindowTitle("Calibrate arms");
  State& s = *s_;
  const QFont mono = QFontDatabase::systemFont(QFontDatabase::FixedFont);

  // The arms: where, what scan and info say.
  auto* arms_box = new QGroupBox("Arms", this);
  s.bus_label = Named(new QLabel(Q("Bus: " + c::Describe(options.bus))), "bus_label");
  s.arms_view = Named(new QPlainTextEdit, "arms_view");
  s.arms_view->setReadOnly(true);
  s.arms_view->setFont(mono);
  s.arms_view->setLineWrapMode(QPlainTextEdit::NoWrap);  // info's columns as the terminal shows them
  s.arms_view->setMinimumHeight(120);
  s.scan_button = Named(new QPushButton("&Scan"), "scan_button");
  s.info_button = Named(new QPushButton("&Info"), "info_button");
  s.arm_choice = Named(new QComboBox, "arm_choice");
  s.arm_choice->addItem("arm 1 (left)", 1);
  s.arm_choice->addItem("arm 2 (right)", 2);
  auto* arms_row = new QHBoxLayout;
  arms_row->addWidget(s.arm_choice);
  arms_row->addWidget(s.scan_button);
  arms_row->addWidget(s.info_button);
  arms_row->addStretch();
  auto* arms_layout = new QVBoxLayout(arms_box);
  arms_layout->addWidget(s.bus_label);
  arms_layout->addLayout(arms_row);
  arms_layout->addWidget(s.arms_view);

  // The calibration: what, progress, stop.
  auto* run_box = new QGroupBox("Calibration", this);
  s.joint_choice = Named(new QComboBox, "joint_choice");
  s.joint_choice->addItem("all joints", 0b111);
  s.joint_choice->addItem("yaw", 0b001);
  s.joint_choice->addItem("pitch", 0b010);
  s.joint_choice->addItem("insertion", 0b100);
  s.step_choice = Named(new QComboBox, "step_choice");
  s.step_choice->addItem("all steps", -1);
  for (const c::StepInfo& i : c::AllSteps()) s.step_choice->addItem(i.name, static_cast<int>(i.step));
  s.calibrate_button = Named(new QPushButton("&Calibrate"), "calibrate_button");
  s.abort_button = Named(new QPushButton("&Abort"), "abort_button");
  s.abort_button->setEnabled(false);
  s.abort_button->setStyleSheet("QPushButton:enabled { color: white; background: #b22222; font-weight: bold; }");
  auto* run_row = new QHBoxLayout;
  run_row->addWidget(s.joint_choice);
  run_row->addWidget(s.step_choice);
  run_row->addWidget(s.calibrate_button);
  run_row->addStretch();
  run_row->addWidget(s.abort_button);
  s.steps_list = Named(new QListWidget, "steps_list");
  s.steps_list->setMaximumWidth(260);
  s.step_label = Named(new QLabel("idle"), "step_label");
  s.step_progress = Named(new QProgressBar, "step_progress");
  s.step_progress->setRange(0, 1000);
  s.step_progress->setValue(0);
  s.step_progress->setFormat("%p%");
  s.log = Named(new QPlainTextEdit, "log");
  s.log->setReadOnly(true);
  s.log->setFont(mono);
  s.log->setLineWrapMode(QPlainTextEdit::NoWrap);
  auto* progress_column = new QVBoxLayout;
  progress_column->addWidget(s.step_label);
  progress_column->addWidget(s.step_progress);
  progress_column->addWidget(s.log);
  auto* progress_row = new QHBoxLayout;
  progress_row->addWidget(s.steps_list);
  progress_row->addLayout(progress_column, 1);
  s.hand_box = Named(new QGroupBox("Move the arm by hand"), "hand_box");
  s.hand_instruction = Named(new QLabel, "hand_instruction");
  s.hand_instruction->setWordWrap(true);
  s.hand_live = Named(new QLabel, "hand_live");
  s.hand_live->setFont(mono);
  s.hand_accept = Named(new QPushButton("Take this &value"), "hand_accept");
  s.hand_retry = Named(new QPushButton("Start the step a&gain"), "hand_retry");
  auto* hand_row = new QHBoxLayout;
  hand_row->addWidget(s.hand_live, 1);
  hand_row->addWidget(s.hand_accept);
  hand_row->addWidget(s.hand_retry);
  auto* hand_layout = new QVBoxLayout(s.hand_box);
  hand_layout->addWidget(s.hand_instruction);
  hand_layout->addLayout(hand_row);
  s.hand_box->hide();
  auto* run_layout = new QVBoxLayout(run_box);
  run_layout->addLayout(run_row);
  run_layout->addWidget(s.hand_box);
  run_layout->addLayout(progress_row);

  // The result: every check and the report.
  auto* result_box = new QGroupBox("Result", this);
  s.results = Named(new QTableWidget(0, 4), "results_table");
  s.results->setHorizontalHeaderLabels({"check", "measured", "tolerance", "result"});
  s.results->horizontalHeader()->setSectionResizeMode(0, QHeaderView::Stretch);
  s.results->verticalHeader()->hide();
  s.results->setEditTriggers(QAbstractItemView::NoEditTriggers);
  s.result_label = Named(new QLabel, "result_label");
  s.result_label->setWordWrap(true);
  s.open_report = Named(new QPushButton("Open &report"), "open_report_button");
  s.open_report->setEnabled(false);
  auto* result_row = new QHBoxLayout;
  result_row->addWidget(s.result_label, 1);
  result_row->addWidget(s.open_report);
  auto* result_layout = new QVBoxLayout(result_box);
  result_layout->addWidget(s.results);
  result_layout->addLayout(result_row);

  auto* close = Named(new QPushButton("Close"), "close_button");
  auto* bottom = new QHBoxLayout;
  bottom->addStretch();
  bottom->addWidget(close);
  auto* top = new QHBoxLayout;
  top->addWidget(arms_box, 2);
  top->addWidget(result_box, 3);
  auto* layout = new QVBoxLayout(this);
  layout->addLayout(top, 3);
  layout->addWidget(run_box, 2);
  layout->addLayout(bottom);

  connect(s.scan_button, &QPushButton::clicked, this, [this] { StartScan(); });
  connect(s.info_button, &QPushButton::clicked, this, [this] { StartInfo(); });
  connect(s.calibrate_button, &QPushButton::clicked, this, [this] { StartCalibrate(); });
  connect(s.abort_button, &QPushButton::clicked, this, [this] { Abort(); });
  connect(s.open_report, &QPushButton::clicked, this,
          [this] { QDesktopServices::openUrl(QUrl::fromLocalFile(Q(s_->report_html))); });
  connect(close, &QPushButton::clicked, this, [this] { reject(); });
  connect(s.hand_accept, &QPushButton::clicked, this, [this] {
    s_->ui->HandAnswered(c::HandAnswer::kAccept);
    s_->hand_accept->setEnabled(false);
    s_->hand_retry->setEnabled(false);
  });
  connect(s.hand_retry, &QPushButton::clicked, this, [this] {
    s_->ui->HandAnswered(c::HandAnswer::kRetry);
    s_->hand_accept->setEnabled(false);
    s_->hand_retry->setEnabled(false);
  });

  CalibrationPanelHandlers handlers;
  handlers.progress = [this](int arm, const std::string& step, double f, double eta) {
    ShowProgress(arm, step, f, eta);
  };
  handlers.note = [this](const std::string& line) { s_->log->appendPlainText(Q(line)); };
  handlers.ask = [this](const c::MotionNotice& notice, std::function<void(bool)> answer) {
    auto* box = new QMessageBox(QMessageBox::Question, "Calibrate arms: the arm will move", Q(MotionQuestion(notice)),
                                QMessageBox::Yes | QMessageBox::No, this);
    box->setObjectName("motion_prompt");
    box->setDefaultButton(QMessageBox::No);  // as the terminal's [y/N]
    box->setAttribute(Qt::WA_DeleteOnClose);
    connect(box, &QMessageBox::finished, this, [box, answer] { answer(box->result() == QMessageBox::Yes); });
    box->open();
  };
  handlers.hand_prompt = [this](const c::HandPrompt& p) {
    State& st = *s_;
    std::string title = "arm " + std::to_string(p.arm) + " " + p.step + " (" + std::to_string(p.prompt_index + 1) +
                        " of " + std::to_string(p.prompt_count);
    if (p.attempt > 1) title += ", try " + std::to_string(p.attempt);
    st.hand_box->setTitle(Q(title + ")"));
    std::string text = p.instruction;
    if (!p.retry_reason.empty()) text = "Again: " + p.retry_reason + ".\n" + text;
    st.hand_instruction->setText(Q(text));
    st.hand_live->setText("live: --");
    st.hand_accept->setEnabled(true);
    st.hand_retry->setEnabled(true);
    st.hand_box->show();
    st.log->appendPlainText(Q(title + "): " + p.instruction));
  };
  handlers.hand_live = [this](const c::HandPrompt& p, double v) {
    s_->hand_live->setText(QString("live: %1 %2").arg(v, 0, 'f', p.unit == "counts" ? 0 : 4).arg(Q(p.unit)));
  };
  s.ui = std::make_unique<CalibrationPanelUi>(this, std::move(handlers), &s.abort);
  resize(1100, 720);
  StartScan();
}

CalibrationPanel* CalibrationPanel::ForTrainer(const Scenario& scenario, int arms_udp_base_port, QWidget* parent) {
  c::ToolOptions options;
  options.bus = CalibrationBusOf(scenario, arms_udp_base_port);
  return new CalibrationPanel(options, parent);
}

CalibrationPanel::~CalibrationPanel() {
  s_->abort = true;
  if (s_->worker.joinable()) s_->worker.join();
}

bool CalibrationPanel::busy() const { return s_->running.load(); }
const c::CommandOutcome& CalibrationPanel::last_outcome() const { return s_->outcome; }
c::ToolSession* CalibrationPanel::last_session() { return busy() ? nullptr : s_->session.get(); }
std::string CalibrationPanel::report_html() const { return s_->report_html; }

void CalibrationPanel::StartScan() { Run("scan", 0); }
void CalibrationPanel::StartInfo() { Run("info", s_->arm_choice->currentData().toInt()); }
void CalibrationPanel::StartCalibrate() { Run("calibrate", s_->arm_choice->currentData().toInt()); }

void CalibrationPanel::Abort() {
  if (!busy()) return;
  s_->abort = true;
  s_->log->appendPlainText("Abort pressed: stopping the arm");
  s_->abort_button->setEnabled(false);
}

void CalibrationPanel::done(int result) {
  // Stop what runs, then let go of the bus (its ports or interface) before anyone takes it back.
  s_->abort = true;
  if (s_->worker.joinable()) s_->worker.join();
  s_->running = false;
  s_->session.reset();
  QDialog::done(result);
}

void CalibrationPanel::Run(const std::string& command, int arm) {
  State& s = *s_;
  if (busy()) return;
  if (s.worker.joinable()) s.worker.join();  // the previous one has ended (Finished)
  s.abort = false;
  s.running = true;
  s.command = command;
  for (QWidget* w : std::initializer_list<QWidget*>{s.scan_button, s.info_button, s.calibrate_button, s.arm_choice,
                                                    s.joint_choice, s.step_choice})
    w->setEnabled(false);
  s.abort_button->setEnabled(true);
  c::CalibrateRequest request;
  request.joints = static_cast<unsigned>(s.joint_choice->currentData().toInt());
  if (const int step = s.step_choice->currentData().toInt(); step >= 0) request.steps = {static_cast<c::Step>(step)};
  if (command == "calibrate") {
    s.steps_list->clear();
    for (const std::string& row : StepRows(request.steps)) {
      auto* item = new QListWidgetItem(Q("   " + row), s.steps_list);
      item->setData(Qt::UserRole, Q(row));  // the step's name as the commands report it
    }
    s.results->setRowCount(0);
    s.result_label->clear();
    s.open_report->setEnabled(false);
    s.report_html.clear();
    s.step_progress->setValue(0);
    s.step_label->setText(Q("arm " + std::to_string(arm) + ": waiting for the arm"));
  }
  s.log->appendPlainText(Q(command + (arm ? " arm " + std::to_string(arm) : std::string()) + " ..."));
  c::ToolOptions options = s.options;
  options.command = command;
  // The worker owns the session while it runs: the previous one (and its bus) goes first, so
  // that the new one can bind the same ports and its emulated arms boot from the saved flash.
  s.worker = std::thread([this, options, command, arm, request] {
    State& st = *s_;
    c::CommandOutcome o;
    try {
      st.session.reset();
      st.session = std::make_unique<c::ToolSession>(options, *st.ui, &st.abort);
      if (command == "scan")
        o = c::Scan(*st.session);
      else if (command == "info")
        o = c::Info(*st.session, arm);
      else
        o = c::Calibrate(*st.session, arm, request);
      st.session->bus().Flush();
    } catch (const std::exception& e) {
      o = c::ToolSession::Failure(c::kExitInternal, std::string("internal error: ") + e.what());
    }
    st.outcome = std::move(o);
    QMetaObject::invokeMethod(
        this, [this] { Finished(); }, Qt::QueuedConnection);
  });
}

void CalibrationPanel::ShowProgress(int arm, const std::string& step, double fraction, double eta_s) {
  State& s = *s_;
  // Steps before this one are done; this one shows its fraction and time left.
  for (int i = 0; i < s.steps_list->count(); ++i) {
    QListWidgetItem* item = s.steps_list->item(i);
    const QString name = item->data(Qt::UserRole).toString();
    if (name.toStdString() != step) continue;
    for (int k = 0; k < i; ++k) {
      QListWidgetItem* done = s.steps_list->item(k);
      done->setText("✓  " + done->data(Qt::UserRole).toString());
    }
    item->setText((fraction >= 1.0 ? "✓  " : "▶  ") + name);
    s.steps_list->setCurrentRow(i);
  }
  s.step_progress->setValue(static_cast<int>(std::lround(1000 * std::clamp(fraction, 0.0, 1.0))));
  s.step_label->setText(Q("arm " + std::to_string(arm) + " " + step + ": " +
                          std::to_string(static_cast<int>(std::lround(100 * fraction))) + " %, " + c::FormatEta(eta_s) +
                          " left"));
}

void CalibrationPanel::Finished() {
  State& s = *s_;
  if (s.worker.joinable()) s.worker.join();
  s.running = false;
  for (QWidget* w : std::initializer_list<QWidget*>{s.scan_button, s.info_button, s.calibrate_button, s.arm_choice,
                                                    s.joint_choice, s.step_choice})
    w->setEnabled(true);
  s.abort_button->setEnabled(false);
  s.hand_box->hide();
  const c::CommandOutcome& o = s.outcome;
  if (s.command == "scan" || s.command == "info") {
    // What the command line prints, as it prints it.
    if (s.command == "scan") s.arms_view->clear();
    s.arms_view->appendPlainText(Q(o.text));
    if (o.exit_code != c::kExitOk) s.log->appendPlainText(Q(o.text));
    return;
  }
  ShowResults();
}

void CalibrationPanel::ShowResults() {
  State& s = *s_;
  const c::CommandOutcome& o = s.outcome;
  const nlohmann::json& j = o.json;
  if (j.contains("checks")) {
    s.results->setRowCount(static_cast<int>(j["checks"].size()));
    int row = 0;
    for (const nlohmann::json& check : j["checks"]) {
      const std::string unit = check.value("unit", "");
      const bool pass = check.value("pass", false);
      auto* name = new QTableWidgetItem(Q(check.value("name", "")));
      auto* value = new QTableWidgetItem(Number(check.value("value", 0.0), unit));
      auto* tolerance = new QTableWidgetItem(QString::number(check.value("min", 0.0), 'g', 4) + " .. " +
                                             Number(check.value("max", 0.0), unit));
      auto* verdict = new QTableWidgetItem(pass ? "pass" : "FAIL");
      verdict->setForeground(pass ? QColor(0, 128, 0) : QColor(200, 0, 0));
      s.results->setItem(row, 0, name);
      s.results->setItem(row, 1, value);
      s.results->setItem(row, 2, tolerance);
      s.results->setItem(row, 3, verdict);
      ++row;
    }
    s.results->resizeColumnsToContents();
  }
  if (j.contains("files") && j["files"].contains("report_html") && j.contains("session_dir")) {
    s.report_html = j["session_dir"].get<std::string>() + "/" + j["files"]["report_html"].get<std::string>();
    s.open_report->setEnabled(QFileInfo::exists(Q(s.report_html)));
  }
  // The command's own last lines: PASS/FAIL and where the report is, or why it stopped.
  std::string summary = o.text;
  if (o.exit_code == c::kExitOk) {
    const std::size_t pass = summary.rfind("PASS");
    if (pass != std::string::npos) summary = summary.substr(pass);
    s.step_label->setText("done");
    for (int i = 0; i < s.steps_list->count(); ++i)
      s.steps_list->item(i)->setText("✓  " + s.steps_list->item(i)->data(Qt::UserRole).toString());
  } else {
    s.step_label->setText(Q(std::string("stopped: ") + c::ExitName(o.exit_code)));
  }
  while (!summary.empty() && summary.back() == '\n') summary.pop_back();
  s.result_label->setText(Q(summary));
  s.result_label->setStyleSheet(o.exit_code == c::kExitOk ? "QLabel { color: #006400; font-weight: bold; }"
                                                          : "QLabel { color: #b22222; font-weight: bold; }");
  s.log->appendPlainText(Q(o.text));
}

}  // namespace vesica::app
