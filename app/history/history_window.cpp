#include "app/history/history_window.h"

#include <QComboBox>
#include <QDateTime>
#include <QDir>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QSaveFile>
#include <QSplitter>
#include <QTableWidget>
#include <QVBoxLayout>
#include <algorithm>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include "app/history/learning_curve_plot.h"
#include "app/history/metric_format.h"
#include "app/history/metrics_panel.h"
#include "app/history/plot_metrics.h"

namespace vesica::app {
namespace {

SessionStore& Checked(const std::unique_ptr<SessionStore>& store) {
  if (!store) throw std::invalid_argument("HistoryWindow: the session store is null");
  return *store;
}

const char* const kColumns[] = {"#", "Started (UTC)", "Procedure", "Scenario", "Duration", "Success", "Slips",
                                "Path (cm)", "Liver damage (mm²)", "Max force (N)", "Tissue removed (%)",
                                // The Calot step (issue 36): "–" for a session without it.
                                "Critical view", "Bleeds", "Bile duct injuries"};
constexpr int kColumnCount = static_cast<int>(std::size(kColumns));

QString Text(const std::string& utf8) { return QString::fromStdString(utf8); }

}  // namespace

HistoryWindow::HistoryWindow(SessionStore& store, QWidget* parent) : QWidget(parent), store_(store) {
  BuildUi();
  Reload();
}

HistoryWindow::HistoryWindow(std::unique_ptr<SessionStore> store, QWidget* parent)
    : QWidget(parent), owned_store_(std::move(store)), store_(Checked(owned_store_)) {
  BuildUi();
  Reload();
}

HistoryWindow::~HistoryWindow() = default;

void HistoryWindow::BuildUi() {
  setWindowTitle(QString::fromUtf8("Vesica — session history (") + Text(store_.Describe()) + ")");

  trainees_ = new QComboBox(this);
  trainees_->setObjectName(QStringLiteral("trainee_combo"));
  trainees_->setSizeAdjustPolicy(QComboBox::AdjustToContents);
  metrics_ = new QComboBox(this);
  metrics_->setObjectName(QStringLiteral("metric_combo"));
  for (const PlotMetric& metric : kPlotMetrics) metrics_->addItem(Text(AxisTitle(metric)), QString(metric.key));
  export_ = new QPushButton(QStringLiteral("Export CSV..."), this);
  export_->setObjectName(QStringLiteral("export_csv_button"));

  plot_ = new LearningCurvePlot(this);
  plot_->setObjectName(QStringLiteral("learning_curve"));

  table_ = new QTableWidget(0, kColumnCount, this);
  table_->setObjectName(QStringLiteral("sessions_table"));
  QStringList headers;
  for (const char* column : kColumns) headers << QString::fromUtf8(column);
  table_->setHorizontalHeaderLabels(headers);
  table_->verticalHeader()->setVisible(false);
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table_->setSelectionBehavior(QAbstractItemView::SelectRows);
  table_->setSelectionMode(QAbstractItemView::SingleSelection);

  panel_ = new MetricsPanel(this);
  panel_->setObjectName(QStringLiteral("metrics_panel"));

  status_ = new QLabel(this);
  status_->setObjectName(QStringLiteral("status_label"));
  status_->setWordWrap(true);
  status_->setTextInteractionFlags(Qt::TextSelectableByMouse);

  auto* choosers = new QHBoxLayout;
  choosers->addWidget(new QLabel(QStringLiteral("Trainee:"), this));
  choosers->addWidget(trainees_);
  choosers->addSpacing(12);
  choosers->addWidget(new QLabel(QStringLiteral("Metric:"), this));
  choosers->addWidget(metrics_);
  choosers->addStretch(1);
  choosers->addWidget(export_);

  auto* lower = new QSplitter(Qt::Horizontal);
  lower->addWidget(table_);
  lower->addWidget(panel_);
  lower->setStretchFactor(0, 3);
  lower->setStretchFactor(1, 1);
  auto* split = new QSplitter(Qt::Vertical);
  split->addWidget(plot_);
  split->addWidget(lower);
  split->setStretchFactor(0, 1);
  split->setStretchFactor(1, 1);

  auto* layout = new QVBoxLayout(this);
  layout->addLayout(choosers);
  layout->addWidget(split, 1);
  layout->addWidget(status_);
  resize(960, 680);

  connect(trainees_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this](int index) {
    if (!filling_choosers_ && index >= 0) LoadTrainee(trainees_->itemText(index));
  });
  connect(metrics_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this](int index) {
    if (index >= 0) PlotSessions();
  });
  connect(table_, &QTableWidget::itemSelectionChanged, this, [this] { ShowRow(table_->currentRow()); });
  connect(export_, &QPushButton::clicked, this, [this] { ExportWithDialog(); });
}

bool HistoryWindow::Reload() {
  const QString keep = CurrentTrainee();
  std::vector<std::string> ids;
  try {
    ids = store_.ListTrainees();
  } catch (const std::exception& e) {
    filling_choosers_ = true;
    trainees_->clear();
    filling_choosers_ = false;
    sessions_.clear();
    plot_->SetSessions({});
    plot_->SetEmptyText(QStringLiteral("Could not read the trainees"));
    FillTable();
    export_->setEnabled(false);
    SetStatus(QStringLiteral("Error: ") + Text(e.what()), true);
    return false;
  }
  filling_choosers_ = true;
  trainees_->clear();
  for (const std::string& id : ids) trainees_->addItem(Text(id));
  const int index = ids.empty() ? -1 : std::max(0, trainees_->findText(keep));
  trainees_->setCurrentIndex(index);
  filling_choosers_ = false;
  trainees_->setEnabled(!ids.empty());
  if (ids.empty()) {
    sessions_.clear();
    plot_->SetSessions({});
    plot_->SetEmptyText(QStringLiteral("No sessions recorded yet"));
    FillTable();
    export_->setEnabled(false);
    SetStatus(QStringLiteral("No sessions recorded in ") + Text(store_.Describe()), false);
    return true;
  }
  return LoadTrainee(trainees_->itemText(index));
}

bool HistoryWindow::SelectTrainee(const QString& trainee_id) {
  const int index = trainees_->findText(trainee_id);
  if (index < 0) {
    SetStatus(QStringLiteral("Error: trainee '%1' has no sessions").arg(trainee_id), true);
    return false;
  }
  filling_choosers_ = true;
  trainees_->setCurrentIndex(index);
  filling_choosers_ = false;
  return LoadTrainee(trainee_id);
}

QString HistoryWindow::CurrentTrainee() const {
  return trainees_->currentIndex() < 0 ? QString() : trainees_->currentText();
}

bool HistoryWindow::SelectMetric(const QString& key) {
  const int index = FindPlotMetric(key.toStdString());
  if (index < 0) return false;
  metrics_->setCurrentIndex(index);  // the chooser's signal sets the plot's metric
  return true;
}

bool HistoryWindow::LoadTrainee(const QString& trainee_id) {
  try {
    sessions_ = store_.List(trainee_id.toStdString());
  } catch (const std::exception& e) {
    sessions_.clear();
    plot_->SetSessions({});
    plot_->SetEmptyText(QStringLiteral("Could not read the sessions of %1").arg(trainee_id));
    FillTable();
    export_->setEnabled(false);
    SetStatus(QStringLiteral("Error: ") + Text(e.what()), true);
    return false;
  }
  const auto replays = std::count_if(sessions_.begin(), sessions_.end(),
                                     [](const StoredSession& session) { return session.record.replay; });
  PlotSessions();
  FillTable();
  export_->setEnabled(!sessions_.empty());
  QString status =
      QStringLiteral("%1 session(s) of %2 in %3").arg(sessions_.size()).arg(trainee_id, Text(store_.Describe()));
  if (replays > 0) status += QStringLiteral("; %1 replay(s) listed, not plotted").arg(replays);
  SetStatus(status, false);
  return true;
}

void HistoryWindow::PlotSessions() {
  const int index = std::max(0, metrics_->currentIndex());
  const PlotMetric& metric = kPlotMetrics[index];
  // A replay (or the demo) is not the trainee's own hands: listed, never a step of the curve.
  std::vector<SessionMetrics> metrics;
  for (const StoredSession& session : sessions_)
    if (!session.record.replay && session.record.procedure == metric.procedure &&
        PlotsSession(metric, session.record.metrics))
      metrics.push_back(session.record.metrics);
  plot_->SetSessions(std::move(metrics));
  plot_->SetMetric(index);
  const QString trainee = CurrentTrainee();
  plot_->SetEmptyText(trainee.isEmpty() ? QStringLiteral("No sessions recorded yet")
                      : metric.measured == nullptr
                          ? QStringLiteral("No %1 sessions of %2")
                                .arg(QString::fromLatin1(ProcedureTitle(metric.procedure)).toLower(), trainee)
                          : QStringLiteral("No sessions of %1 with this measure").arg(trainee));
}

void HistoryWindow::FillTable() {
  const QSignalBlocker block(table_);
  table_->clearContents();
  table_->setRowCount(static_cast<int>(sessions_.size()));
  for (int row = 0; row < static_cast<int>(sessions_.size()); ++row) {
    const SessionRecord& r = sessions_[row].record;
    const SessionMetrics& m = r.metrics;
    const bool biopsy = r.procedure == Procedure::kNeedleBiopsy;
    const QString none = QString::fromUtf8("–");  // a cholecystectomy measure of a biopsy
    const QString cells[kColumnCount] = {
        QString::number(row + 1),
        QDateTime::fromSecsSinceEpoch(r.started_unix_s, Qt::UTC).toString(QStringLiteral("yyyy-MM-dd HH:mm")),
        QString::fromLatin1(ProcedureTitle(r.procedure)),
        Text(r.scenario),
        Text(FormatMinutesSeconds(m.duration_s)),
        r.replay       ? QStringLiteral("replay")
        : r.unfinished ? QStringLiteral("unfinished")
        : m.success    ? QStringLiteral("yes")
                       : QStringLiteral("no"),
        biopsy ? none : QString::number(m.slips),
        biopsy ? none : Text(FormatCentimetres(m.path_length_left_m + m.path_length_right_m)),
        biopsy ? none : Text(FormatSquareMillimetres(m.liver_damage_m2)),
        Text(FormatNewtons(m.max_force_N)),
        biopsy ? none : Text(FormatPercent(m.tissue_removed_fraction)),
        Text(FormatCriticalViewShort(m)),
        m.calot_step ? QString::number(m.bleeding_events) : none,
        m.calot_step ? QString::number(m.bile_duct_injuries) : none};
    for (int column = 0; column < kColumnCount; ++column) {
      auto* item = new QTableWidgetItem(cells[column]);
      if (column < 1 || column > 3) item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
      table_->setItem(row, column, item);
    }
  }
  table_->resizeColumnsToContents();
  // The newest session is the one a trainee usually looks at first.
  if (sessions_.empty()) {
    panel_->Clear();
  } else {
    table_->selectRow(static_cast<int>(sessions_.size()) - 1);
    ShowRow(static_cast<int>(sessions_.size()) - 1);
  }
}

void HistoryWindow::ShowRow(int row) {
  if (row < 0 || row >= static_cast<int>(sessions_.size())) {
    panel_->Clear();
    return;
  }
  panel_->Show(sessions_[row].record.metrics, sessions_[row].record.procedure);
}

bool HistoryWindow::ExportCsvTo(const QString& path) {
  const QString trainee = CurrentTrainee();
  if (trainee.isEmpty()) {
    SetStatus(QStringLiteral("Error: export CSV: no trainee selected"), true);
    return false;
  }
  std::ostringstream csv;
  try {
    store_.ExportCsv(trainee.toStdString(), csv);
  } catch (const std::exception& e) {
    SetStatus(QStringLiteral("Error: export CSV: ") + Text(e.what()), true);
    return false;
  }
  const std::string bytes = csv.str();
  QSaveFile file(path);
  if (!file.open(QIODevice::WriteOnly) ||
      file.write(bytes.data(), static_cast<qint64>(bytes.size())) != static_cast<qint64>(bytes.size()) ||
      !file.commit()) {
    SetStatus(QStringLiteral("Error: export CSV to %1: %2").arg(path, file.errorString()), true);
    return false;
  }
  const auto rows = std::count(bytes.begin(), bytes.end(), '\n') - 1;  // less the header
  SetStatus(QStringLiteral("Exported %1 session(s) of %2 to %3").arg(rows).arg(trainee, path), false);
  return true;
}

void HistoryWindow::ExportWithDialog() {
  const QString trainee = CurrentTrainee();
  if (trainee.isEmpty()) return;
  const QString path =
      QFileDialog::getSaveFileName(this, QStringLiteral("Export CSV"), QDir::home().filePath(trainee + "-sessions.csv"),
                                   QStringLiteral("CSV files (*.csv);;All files (*)"));
  if (!path.isEmpty()) ExportCsvTo(path);
}

QString HistoryWindow::StatusText() const { return status_->text(); }

void HistoryWindow::SetStatus(const QString& text, bool is_error) {
  status_is_error_ = is_error;
  status_->setText(text);
  status_->setStyleSheet(is_error ? QStringLiteral("color: #b00020;") : QString());
}

}  // namespace vesica::app
