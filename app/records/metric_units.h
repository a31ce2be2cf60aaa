#pragma once
// The one unit system of everything a person reads: the trainer's metrics panel and history
// (app/history/plot_metrics.h uses the same units and factors), `vesica-records list` and the CSV
// export: seconds, centimetres, square millimetres, newtons, percent and counts. The stores keep
// SI (metric_fields.h); each CSV column's name carries its display unit.

#include <array>
#include <string_view>

#include "app/records/metric_fields.h"

namespace vesica::app {

struct MetricDisplayUnit {
  const char* field;       // the kMetricFields name (SI, as stored)
  const char* csv_column;  // the CSV column, named with the display unit
  const char* unit;        // "cm", "mm²" (UTF-8), ""  for counts and flags
  double scale;            // display value = stored SI value * scale
};

/// In kMetricFields order.
inline constexpr std::array<MetricDisplayUnit, kMetricFields.size()> kMetricDisplayUnits{{
    {"duration_s", "duration_s", "s", 1.0},
    {"path_length_left_m", "path_length_left_cm", "cm", 100.0},
    {"path_length_right_m", "path_length_right_cm", "cm", 100.0},
    {"slips", "slips", "", 1.0},
    {"cautery_on_s", "cautery_on_s", "s", 1.0},
    {"liver_damage_m2", "liver_damage_mm2", "mm²", 1e6},
    {"gallbladder_damage_m2", "gallbladder_damage_mm2", "mm²", 1e6},
    {"max_force_N", "max_force_N", "N", 1.0},
    {"mean_force_N", "mean_force_N", "N", 1.0},
    {"tissue_removed_fraction", "tissue_removed_percent", "%", 100.0},
    {"springs_cut", "springs_cut", "", 1.0},
    {"springs_total", "springs_total", "", 1.0},
    {"gallbladder_free", "gallbladder_free", "", 1.0},
    {"perforation", "perforation", "", 1.0},
    {"success", "success", "", 1.0},
    {"biopsy_sampled", "biopsy_sampled", "", 1.0},
    {"time_to_sample_s", "time_to_sample_s", "s", 1.0},
    {"sample_distance_m", "sample_distance_mm", "mm", 1e3},
    {"nogo_crossings", "nogo_crossings", "", 1.0},
    {"insertion_attempts", "insertion_attempts", "", 1.0},
    {"calot_step", "calot_step", "", 1.0},
    {"cvs_achieved", "cvs_achieved", "", 1.0},
    {"cvs_time_s", "cvs_time_s", "s", 1.0},
    {"cvs_before_first_clip", "cvs_before_first_clip", "", 1.0},
    {"cystic_duct_clips", "cystic_duct_clips", "", 1.0},
    {"cystic_artery_clips", "cystic_artery_clips", "", 1.0},
    {"cystic_duct_clips_correct", "cystic_duct_clips_correct", "", 1.0},
    {"cystic_artery_clips_correct", "cystic_artery_clips_correct", "", 1.0},
    {"cystic_duct_divided_between_clips", "cystic_duct_divided_between_clips", "", 1.0},
    {"cystic_artery_divided_between_clips", "cystic_artery_divided_between_clips", "", 1.0},
    {"bleeding_events", "bleeding_events", "", 1.0},
    {"bile_leaks", "bile_leaks", "", 1.0},
    {"bile_duct_injuries", "bile_duct_injuries", "", 1.0},
    {"calot_passed", "calot_passed", "", 1.0},
}};

consteval bool DisplayUnitsFollowMetricFields() {
  for (std::size_t i = 0; i < kMetricFields.size(); ++i)
    if (std::string_view(kMetricFields[i].name) != kMetricDisplayUnits[i].field) return false;
  return true;
}
static_assert(DisplayUnitsFollowMetricFields(), "kMetricDisplayUnits must list kMetricFields in order");

/// The display unit of the metric stored under `field` (a kMetricFields name), or nullptr.
constexpr const MetricDisplayUnit* FindMetricDisplayUnit(std::string_view field) {
  for (const auto& unit : kMetricDisplayUnits)
    if (field == unit.field) return &unit;
  return nullptr;
}

}  // namespace vesica::app
