#include "tests/records/sample_records.h"

namespace vesica::app::testing {

SessionRecord SampleRecord(int index, const std::string& trainee_id) {
  SessionRecord r;
  r.trainee_id = trainee_id;
  r.scenario = "cholecystectomy-" + std::to_string(index % 3);
  r.station = "station-" + std::to_string(index % 2 + 1);
  r.started_unix_s = 1795406400 + 600 * static_cast<std::int64_t>(index);
  r.ended_unix_s = r.started_unix_s + 300 + index;
  r.input_recording_path = "/var/lib/vesica/recordings/" + std::to_string(index) + ".rec";
  r.replay = index % 4 == 3;
  r.unfinished = index % 5 == 4;
  r.physics_lag_s = 0.125 * index + 1.0 / 3.0;
  SessionMetrics& m = r.metrics;
  const double x = index + 1;
  m.duration_s = 299.75 + x / 3.0;
  m.path_length_left_m = 1.0 / 7.0 * x;
  m.path_length_right_m = 0.1 * x + 1e-12;
  m.slips = 3 + index;
  m.cautery_on_s = 41.25 / x;
  m.liver_damage_m2 = 1.5e-5 * x;
  m.gallbladder_damage_m2 = 2.0 / 3.0 * 1e-6 * x;
  m.max_force_N = 4.2 + x / 9.0;
  m.mean_force_N = 0.7 + x / 11.0;
  m.tissue_removed_fraction = x / (x + 1.0);
  m.springs_cut = 200 + index;
  m.springs_total = 225 + index;
  m.gallbladder_free = index % 2 == 0;
  m.perforation = index % 3 == 1;
  m.success = m.gallbladder_free && !m.perforation;
  // Every third a needle biopsy, so each store and file round-trips both procedures' columns.
  if (index % 3 == 2) {
    r.procedure = Procedure::kNeedleBiopsy;
    r.scenario = "needle-biopsy-" + std::to_string(index % 2);
  }
  m.biopsy_sampled = index % 2 == 0;
  m.time_to_sample_s = 95.5 + x / 7.0;
  m.sample_distance_m = 0.0035 * x + 1e-9;
  m.nogo_crossings = index % 4;
  m.insertion_attempts = 1 + index;
  // The Calot's triangle step (schema 4) in the cholecystectomies, each flag differing between records.
  if (r.procedure == Procedure::kCholecystectomy) {
    m.calot_step = true;
    m.cvs_achieved = index % 4 != 1;
    m.cvs_time_s = m.cvs_achieved ? 60.0 + x / 7.0 : 0.0;
    m.cvs_before_first_clip = index % 2 == 0;
    m.cystic_duct_clips = 3 + index % 2;
    m.cystic_artery_clips = 2 + index % 3;
    m.cystic_duct_clips_correct = index % 4 == 0;
    m.cystic_artery_clips_correct = index % 4 != 0;
    m.cystic_duct_divided_between_clips = index % 5 != 1;
    m.cystic_artery_divided_between_clips = index % 5 == 1;
    m.bleeding_events = index % 3;
    m.bile_leaks = index % 2;
    m.bile_duct_injuries = index % 7 == 1 ? 1 : 0;
    m.calot_passed = m.cvs_before_first_clip && m.bleeding_events == 0 && m.bile_duct_injuries == 0;
  }
  return r;
}

}  // namespace vesica::app::testing
