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
  bool biopsy_sampled = false;         // a sample was taken
  double time_to_sample_s = 0;         // from the start of the session to the sample
  double sample_distance_m = 0;        // sample site to the tumour's centre (when sampled)
  int nogo_crossings = 0;              // entries of the needle into no-go tissue (lung, bone, ...)
  int insertion_attempts = 0;          // skin entries, the first included
};

}  // namespace vesica::app
