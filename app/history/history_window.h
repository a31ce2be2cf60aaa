#pragma once
// The trainee history view (issue 7): a trainee chooser, a metric chooser, the learning curve of
// that metric over the trainee's sessions, a table of the sessions (start, scenario, duration,
// success, key metrics), the selected session's metrics, and "Export CSV...". Store failures
// (RecordsError) and file errors go to a status label at the bottom, never to a modal box and
// never a crash, so the window stays usable and tests never block.

#include <QString>
#include <QWidget>
#include <memory>
#include <vector>

#include "app/records/session_store.h"

class QComboBox;
class QLabel;
class QPushButton;
class QTableWidget;

namespace vesica::app {

class LearningCurvePlot;
class MetricsPanel;

class HistoryWindow : public QWidget {
 public:
  /// Shows the sessions in `store`, which must outlive the window. Reads the trainee list at
  /// once and selects the first trainee.
  explicit HistoryWindow(SessionStore& store, QWidget* parent = nullptr);
  /// The same, owning the store (the trainer opens one with OpenSessionStore and hands it over).
  explicit HistoryWindow(std::unique_ptr<SessionStore> store, QWidget* parent = nullptr);
  ~HistoryWindow() override;

  /// Re-reads the trainee list and the current trainee's sessions; keeps the selected trainee
  /// when it is still there. Returns false (message in the status label) when the store fails.
  bool Reload();

  /// Selects a trainee of the chooser; false when the trainee has no sessions (is not listed)
  /// or the store fails reading them.
  bool SelectTrainee(const QString& trainee_id);
  /// The selected trainee; empty when there is none.
  QString CurrentTrainee() const;

  /// Selects the plotted metric by kPlotMetrics key ("slips"); false for an unknown key.
  bool SelectMetric(const QString& key);

  /// The selected trainee's sessions as last read, oldest first (table row order).
  const std::vector<StoredSession>& Sessions() const { return sessions_; }

  /// Writes the selected trainee's sessions as CSV (SessionStore::ExportCsv) to `path`,
  /// atomically (a failed export leaves an existing file as it was). Returns false, with the
  /// reason in the status label, when no trainee is selected, the store fails or the file
  /// cannot be written.
  bool ExportCsvTo(const QString& path);

  /// The status line's text, and whether it reports a failure.
  QString StatusText() const;
  bool StatusIsError() const { return status_is_error_; }

  // The parts, for tests and for embedding (objectNames in brackets).
  QComboBox* TraineeChooser() const { return trainees_; }   // "trainee_combo"
  QComboBox* MetricChooser() const { return metrics_; }     // "metric_combo"
  LearningCurvePlot* Plot() const { return plot_; }         // "learning_curve"
  QTableWidget* Table() const { return table_; }            // "sessions_table"
  MetricsPanel* SelectedSession() const { return panel_; }  // "metrics_panel"
  QPushButton* ExportButton() const { return export_; }     // "export_csv_button"
  QLabel* StatusLabel() const { return status_; }           // "status_label"

 private:
  void BuildUi();
  bool LoadTrainee(const QString& trainee_id);
  void FillTable();
  // Gives the plot the trainee's own sessions (no replays) of the chosen metric's procedure.
  void PlotSessions();
  void ShowRow(int row);
  void ExportWithDialog();
  void SetStatus(const QString& text, bool is_error);

  std::unique_ptr<SessionStore> owned_store_;
  SessionStore& store_;
  std::vector<StoredSession> sessions_;
  bool status_is_error_ = false;
  bool filling_choosers_ = false;  // true while Reload repopulates the trainee chooser

  QComboBox* trainees_ = nullptr;
  QComboBox* metrics_ = nullptr;
  QPushButton* export_ = nullptr;
  LearningCurvePlot* plot_ = nullptr;
  QTableWidget* table_ = nullptr;
  MetricsPanel* panel_ = nullptr;
  QLabel* status_ = nullptr;
};

}  // namespace vesica::app
