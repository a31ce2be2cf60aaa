#pragma once
// The critical view of safety (CVS), assessed from the model's state rather than the picture.
//
// Strasberg's three criteria (S. M. Strasberg, L. M. Brunt, "Rationale and use of the critical
// view of safety in laparoscopic cholecystectomy", J Am Coll Surg 211(1):132-138, 2010; first
// described in S. M. Strasberg, M. Hertl, N. J. Soper, J Am Coll Surg 180(1):101-125, 1995):
//   1. the hepatocystic triangle is cleared of fat and fibrous tissue;
//   2. the lower third of the gallbladder is separated from the liver bed (the cystic plate);
//   3. two and only two structures are seen entering the gallbladder.
// The criteria are qualitative; the numbers below are ours, chosen so that a discretised layer
// counts as "cleared" when what is left are strands a surgeon would not take down, and are
// stated here so that an educator can change them in one place.

#include "app/calot/calot_snapshot.h"

namespace vesica::app::calot {

struct CvsThresholds {
  // Criterion 1: fraction of the triangle's fat-and-fibrous layer removed, 0..1. 0.9: the few
  // elements left along the liver edge and the tubes' backs do not hide the triangle.
  double fat_removed_min = 0.9;
  // Criterion 2: fraction of the gallbladder's lower third separated from the liver bed, 0..1.
  // Strasberg asks for the whole third; 0.9 allows the last connective-tissue springs of the
  // model's discretisation (a spring covers several millimetres of bed).
  double lower_third_separated_min = 0.9;
  // Criterion 3: a structure counts as seen when at least this fraction of its length is in the
  // camera's view and not under fat, 0..1. 0.5: its course into the gallbladder can be followed.
  double visible_fraction_min = 0.5;
};

/// Each criterion on its own, so a debrief can say which one was missing.
struct CvsAssessment {
  bool triangle_cleared = false;       // criterion 1
  bool lower_third_separated = false;  // criterion 2
  int structures_seen_entering = 0;    // structures entering the gallbladder that are seen
  bool two_structures_seen = false;    // criterion 3: exactly two

  bool Achieved() const { return triangle_cleared && lower_third_separated && two_structures_seen; }
};

/// Throws CalotInputError for thresholds outside 0..1 (naming the field).
void ValidateThresholds(const CvsThresholds& thresholds);

/// The three criteria for one snapshot (which should have passed ValidateSnapshot).
CvsAssessment AssessCriticalView(const CalotSnapshot& snapshot, const CvsThresholds& thresholds = {});

}  // namespace vesica::app::calot
