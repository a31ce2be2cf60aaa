#pragma once
// The metrics a learning curve can plot, each with its label, display unit and the factor from
// the stored SI value to that unit. Booleans (free, perforation, success, the critical view
// reached) are not plotted; the session table shows them. Each curve is made of one procedure's
// sessions (a biopsy's duration is no step of a cholecystectomy's learning curve).

#include <array>
#include <string>
#include <string_view>

#include "app/records/metric_fields.h"
#include "app/records/procedure.h"

namespace vesica::app {

struct PlotMetric {
  const char* key;                                    // the kMetricFields column name ("liver_damage_m2")
  const char* label;                                  // axis and chooser text ("Liver damage")
  const char* unit;                                   // display unit, UTF-8 ("mm²"); empty for counts
  double scale;                                       // display value = stored SI value * scale
  MetricMember member;                                // the SessionMetrics field
  Procedure procedure = Procedure::kCholecystectomy;  // whose sessions the curve is made of
  // Which of those sessions the metric means something for (nullptr: all of them): the Calot
  // step's counts only for sessions with the step, the time to the critical view only where
  // it was reached.
  bool (*measured)(const SessionMetrics&) = nullptr;
};

/// The session included the Calot's triangle step.
constexpr bool HadCalotStep(const SessionMetrics& m) { return m.calot_step; }
/// The session reached the critical view of safety.
constexpr bool ReachedCriticalView(const SessionMetrics& m) { return m.calot_step && m.cvs_achieved; }

inline constexpr std::array<PlotMetric, 19> kPlotMetrics{{
    {"duration_s", "Duration", "s", 1.0, &SessionMetrics::duration_s},
    {"path_length_left_m", "Path length, grasper", "cm", 100.0, &SessionMetrics::path_length_left_m},
    {"path_length_right_m", "Path length, hook", "cm", 100.0, &SessionMetrics::path_length_right_m},
    {"slips", "Slips", "", 1.0, &SessionMetrics::slips},
    {"cautery_on_s", "Cautery on", "s", 1.0, &SessionMetrics::cautery_on_s},
    {"liver_damage_m2", "Liver damage", "mm²", 1e6, &SessionMetrics::liver_damage_m2},
    {"gallbladder_damage_m2", "Gallbladder damage", "mm²", 1e6, &SessionMetrics::gallbladder_damage_m2},
    {"max_force_N", "Max force", "N", 1.0, &SessionMetrics::max_force_N},
    {"mean_force_N", "Mean force", "N", 1.0, &SessionMetrics::mean_force_N},
    {"tissue_removed_fraction", "Tissue removed", "%", 100.0, &SessionMetrics::tissue_removed_fraction},
    {"springs_cut", "Springs cut", "", 1.0, &SessionMetrics::springs_cut},
    {"time_to_sample_s", "Biopsy: time to sample", "s", 1.0, &SessionMetrics::time_to_sample_s,
     Procedure::kNeedleBiopsy},
    {"sample_distance_m", "Biopsy: sample to tumour centre", "mm", 1e3, &SessionMetrics::sample_distance_m,
     Procedure::kNeedleBiopsy},
    {"nogo_crossings", "Biopsy: no-go crossings", "", 1.0, &SessionMetrics::nogo_crossings, Procedure::kNeedleBiopsy},
    {"insertion_attempts", "Biopsy: insertion attempts", "", 1.0, &SessionMetrics::insertion_attempts,
     Procedure::kNeedleBiopsy},
    {"cvs_time_s", "Calot: time to the critical view", "s", 1.0, &SessionMetrics::cvs_time_s,
     Procedure::kCholecystectomy, ReachedCriticalView},
    {"bleeding_events", "Calot: bleeding events", "", 1.0, &SessionMetrics::bleeding_events,
     Procedure::kCholecystectomy, HadCalotStep},
    {"bile_leaks", "Calot: bile leaks", "", 1.0, &SessionMetrics::bile_leaks, Procedure::kCholecystectomy,
     HadCalotStep},
    {"bile_duct_injuries", "Calot: bile duct injuries", "", 1.0, &SessionMetrics::bile_duct_injuries,
     Procedure::kCholecystectomy, HadCalotStep},
}};

/// Whether a session of the metric's procedure is a point of its curve (PlotMetric::measured).
inline bool PlotsSession(const PlotMetric& metric, const SessionMetrics& metrics) {
  return metric.measured == nullptr || metric.measured(metrics);
}

/// The metric's value for one session in its display unit: stored value * metric.scale.
double PlotValue(const PlotMetric& metric, const SessionMetrics& metrics);

/// The index in kPlotMetrics of the metric with this key, or -1.
int FindPlotMetric(std::string_view key);

/// "Liver damage (mm²)", or the label alone for a unitless metric.
std::string AxisTitle(const PlotMetric& metric);

}  // namespace vesica::app
