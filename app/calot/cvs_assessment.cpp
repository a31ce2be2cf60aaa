#include "app/calot/cvs_assessment.h"

#include <cmath>

namespace vesica::app::calot {

void ValidateThresholds(const CvsThresholds& t) {
  const struct {
    const char* name;
    double value;
  } fields[] = {{"fat_removed_min", t.fat_removed_min},
                {"lower_third_separated_min", t.lower_third_separated_min},
                {"visible_fraction_min", t.visible_fraction_min}};
  for (const auto& field : fields)
    if (!std::isfinite(field.value) || field.value < 0 || field.value > 1)
      throw CalotInputError(std::string("CVS thresholds: ") + field.name + " = " + std::to_string(field.value) +
                            " is outside 0..1");
}

CvsAssessment AssessCriticalView(const CalotSnapshot& snapshot, const CvsThresholds& thresholds) {
  CvsAssessment a;
  a.triangle_cleared = snapshot.fat_removed_fraction >= thresholds.fat_removed_min;
  a.lower_third_separated = snapshot.lower_third_separated_fraction >= thresholds.lower_third_separated_min;
  for (const StructureState& structure : snapshot.structures)
    if (structure.enters_gallbladder && structure.visible_fraction >= thresholds.visible_fraction_min)
      ++a.structures_seen_entering;
  a.two_structures_seen = a.structures_seen_entering == 2;
  return a;
}

}  // namespace vesica::app::calot
