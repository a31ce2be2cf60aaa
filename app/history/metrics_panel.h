#pragma once
// The end-of-session metrics of one session as a labelled form with units: time mm:ss, path
// lengths in cm, burnt areas in mm², forces in N, tissue removed in %, and the outcome with its
// reason. Every value label has an objectName ("metric_slips", listed in kMetricsPanelLabels)
// so tests and scripts can read it; before the first Show the values read "–".

#include <QWidget>
#include <array>

#include "app/records/session_metrics.h"

class QLabel;

namespace vesica::app {

/// The objectNames of the value labels, in form order.
inline constexpr std::array<const char*, 12> kMetricsPanelLabels{
    "metric_duration",   "metric_path_length_left", "metric_path_length_right",  "metric_slips",
    "metric_cautery_on", "metric_liver_damage",     "metric_gallbladder_damage", "metric_max_force",
    "metric_mean_force", "metric_tissue_removed",   "metric_springs_cut",        "metric_success"};

class MetricsPanel : public QWidget {
 public:
  explicit MetricsPanel(QWidget* parent = nullptr);

  /// Shows these metrics (replacing what was shown).
  void Show(const SessionMetrics& metrics);

  /// Back to the "–" placeholders.
  void Clear();

  /// The text of a value label by objectName; empty for an unknown name.
  QString ValueText(const QString& object_name) const;

 private:
  std::array<QLabel*, kMetricsPanelLabels.size()> values_{};
};

}  // namespace vesica::app
