#pragma once
// What one trainee did in one session, as the session code measured it. SI units; the field
// names carry the unit. The column list of every store and of the CSV export is derived from
// this struct through metric_fields.h, so a new field is added there too.

namespace vesica::app {

struct SessionMetrics {
  double duration_s = 0;           // simulated session time
  double path_length_left_m = 0;   // grasper tip path length
  double path_length_right_m = 0;  // hook tip path length
  int slips = 0;
  double cautery_on_s = 0;     // pedal down time
  double liver_damage_m2 = 0;  // area burnt past threshold
  double gallbladder_damage_m2 = 0;
  double max_force_N = 0;              // largest tool-tissue force, either hand
  double mean_force_N = 0;             // mean over steps with contact
  double tissue_removed_fraction = 0;  // membrane elements removed / all
  int springs_cut = 0;
  int springs_total = 0;
  bool gallbladder_free = false;
  bool perforation = false;  // gallbladder wall burnt through past threshold
  bool success = false;      // free and no perforation
  // Needle biopsy (schema version 3; 0 for a cholecystectomy). The cholecystectomy fields above that
  // apply to both keep their meaning: duration_s, max_force_N and mean_force_N (needle force).
  bool biopsy_sampled = false;   // a sample was taken
  double time_to_sample_s = 0;   // from the start of the session to the sample
  double sample_distance_m = 0;  // sample site to the tumour's centre (when sampled)
  int nogo_crossings = 0;        // entries of the needle into no-go tissue (lung, bone, ...)
  int insertion_attempts = 0;    // skin entries, the first included
  // Calot's triangle (schema version 4; issue 36): the step before the liver-bed dissection, in
  // the same cholecystectomy session. All 0 when calot_step is false (a session without the
  // triangle, or stored before version 4): then they mean "not assessed", not "not done".
  bool calot_step = false;                         // the session included the Calot's triangle step
  bool cvs_achieved = false;                       // the critical view of safety was reached
  double cvs_time_s = 0;                           // from the session's start to the critical view (when reached)
  bool cvs_before_first_clip = false;              // reached before any clip was placed
  int cystic_duct_clips = 0;                       // clips placed on the cystic duct(s)
  int cystic_artery_clips = 0;                     // clips placed on the cystic arter(y/ies)
  bool cystic_duct_clips_correct = false;          // >= 2 on the patient's side of the planned cut, >= 1 beyond
  bool cystic_artery_clips_correct = false;        // the same for the artery
  bool cystic_duct_divided_between_clips = false;  // cut, and every cut had a clip on either side
  bool cystic_artery_divided_between_clips = false;
  int bleeding_events = 0;     // the artery cut unclipped on the patient's side, or bleeding reported by the model
  int bile_leaks = 0;          // the cystic duct cut with an open end, or a leak reported by the model
  int bile_duct_injuries = 0;  // clips or cuts on the common bile or hepatic duct (the critical error: ends the case)
  bool calot_passed = false;   // the Calot step's outcome (app/calot/case_outcome.h)
};

}  // namespace vesica::app
