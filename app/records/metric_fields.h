#pragma once
// The one list of SessionMetrics fields: column name, type and member. The SQL schemas, the
// INSERT/SELECT statements and the CSV columns are all generated from it, so they cannot
// disagree with each other or silently drop a field.

#include <array>
#include <variant>

#include "app/records/session_metrics.h"

namespace vesica::app {

using MetricMember = std::variant<double SessionMetrics::*, int SessionMetrics::*, bool SessionMetrics::*>;

struct MetricField {
  const char* name;  // column name in SQL and CSV
  MetricMember member;
  int since_schema = 1;  // the session schema version that added the column (older stores read 0)
};

inline constexpr std::array<MetricField, 34> kMetricFields{{
    {"duration_s", &SessionMetrics::duration_s},
    {"path_length_left_m", &SessionMetrics::path_length_left_m},
    {"path_length_right_m", &SessionMetrics::path_length_right_m},
    {"slips", &SessionMetrics::slips},
    {"cautery_on_s", &SessionMetrics::cautery_on_s},
    {"liver_damage_m2", &SessionMetrics::liver_damage_m2},
    {"gallbladder_damage_m2", &SessionMetrics::gallbladder_damage_m2},
    {"max_force_N", &SessionMetrics::max_force_N},
    {"mean_force_N", &SessionMetrics::mean_force_N},
    {"tissue_removed_fraction", &SessionMetrics::tissue_removed_fraction},
    {"springs_cut", &SessionMetrics::springs_cut},
    {"springs_total", &SessionMetrics::springs_total},
    {"gallbladder_free", &SessionMetrics::gallbladder_free},
    {"perforation", &SessionMetrics::perforation},
    {"success", &SessionMetrics::success},
    {"biopsy_sampled", &SessionMetrics::biopsy_sampled, 3},
    {"time_to_sample_s", &SessionMetrics::time_to_sample_s, 3},
    {"sample_distance_m", &SessionMetrics::sample_distance_m, 3},
    {"nogo_crossings", &SessionMetrics::nogo_crossings, 3},
    {"insertion_attempts", &SessionMetrics::insertion_attempts, 3},
    {"calot_step", &SessionMetrics::calot_step, 4},
    {"cvs_achieved", &SessionMetrics::cvs_achieved, 4},
    {"cvs_time_s", &SessionMetrics::cvs_time_s, 4},
    {"cvs_before_first_clip", &SessionMetrics::cvs_before_first_clip, 4},
    {"cystic_duct_clips", &SessionMetrics::cystic_duct_clips, 4},
    {"cystic_artery_clips", &SessionMetrics::cystic_artery_clips, 4},
    {"cystic_duct_clips_correct", &SessionMetrics::cystic_duct_clips_correct, 4},
    {"cystic_artery_clips_correct", &SessionMetrics::cystic_artery_clips_correct, 4},
    {"cystic_duct_divided_between_clips", &SessionMetrics::cystic_duct_divided_between_clips, 4},
    {"cystic_artery_divided_between_clips", &SessionMetrics::cystic_artery_divided_between_clips, 4},
    {"bleeding_events", &SessionMetrics::bleeding_events, 4},
    {"bile_leaks", &SessionMetrics::bile_leaks, 4},
    {"bile_duct_injuries", &SessionMetrics::bile_duct_injuries, 4},
    {"calot_passed", &SessionMetrics::calot_passed, 4},
}};

/// Field-by-field equality (exact, doubles included: the stores round-trip doubles bit for bit).
inline bool operator==(const SessionMetrics& a, const SessionMetrics& b) {
  for (const auto& field : kMetricFields) {
    const bool same = std::visit([&](auto member) { return a.*member == b.*member; }, field.member);
    if (!same) return false;
  }
  return true;
}

}  // namespace vesica::app
