#pragma once
// The end-of-session metrics of one session as a labelled form with units: time mm:ss, path
// lengths in cm, burnt areas in mm², forces in N, tissue removed in %, and the outcome with its
// reason. Every value label has an objectName ("metric_slips", listed in kMetricsPanelLabels)
// so tests and scripts can read it; before the first Show the values read "–".

#include <QWidget>
#include <array>

#include "app/records/procedure.h"
#include "app/records/session_metrics.h"

class QLabel;

namespace vesica::app {

/// The objectNames of the value labels, in form order.
inline constexpr std::array<const char*, 12> kMetricsPanelLabels{
    "metric_duration",   "metric_path_length_left", "metric_path_length_right",  "metric_slips",
    "metric_cautery_on", "metric_liver_damage",     "metric_gallbladder_damage", "metric_max_force",
    "metric_mean_force", "metric_tissue_removed",   "metric_springs_cut",        "metric_success"};

/// The objectNames of the rows a needle biopsy adds (shown with duration, max and mean force and
/// success; the cholecystectomy's own rows are hidden for a biopsy, and these for a cholecystectomy).
inline constexpr std::array<const char*, 5> kBiopsyPanelLabels{"metric_time_to_sample", "metric_sample_distance",
                                                               "metric_specimen", "metric_nogo_crossings",
                                                               "metric_insertion_attempts"};

/// The objectNames of the rows of the Calot's triangle step (issue 36), shown for a
/// cholecystectomy with metrics.calot_step and hidden otherwise.
inline constexpr std::array<const char*, 8> kCalotPanelLabels{
    "metric_critical_view",   "metric_cystic_duct_clips", "metric_cystic_artery_clips", "metric_division",
    "metric_bleeding_events", "metric_bile_leaks",        "metric_bile_duct_injuries",  "metric_calot_outcome"};

class MetricsPanel : public QWidget {
 public:
  explicit MetricsPanel(QWidget* parent = nullptr);

  /// Shows these metrics (replacing what was shown), with the rows of that procedure (and the
  /// Calot step's when metrics.calot_step).
  void Show(const SessionMetrics& metrics, Procedure procedure = Procedure::kCholecystectomy);

  /// Back to the "–" placeholders.
  void Clear();

  /// The text of a value label by objectName; empty for an unknown name.
  QString ValueText(const QString& object_name) const;

  /// Whether the row with this value objectName is shown (not hidden for the procedure).
  bool RowShown(const QString& object_name) const;

 private:
  void ShowRowsOf(Procedure procedure, bool calot_step);

  std::array<QLabel*, kMetricsPanelLabels.size()> values_{};
  std::array<QLabel*, kMetricsPanelLabels.size()> captions_{};
  std::array<QLabel*, kBiopsyPanelLabels.size()> biopsy_values_{};
  std::array<QLabel*, kBiopsyPanelLabels.size()> biopsy_captions_{};
  std::array<QLabel*, kCalotPanelLabels.size()> calot_values_{};
  std::array<QLabel*, kCalotPanelLabels.size()> calot_captions_{};
};

}  // namespace vesica::app
