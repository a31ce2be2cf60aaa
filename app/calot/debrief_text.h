#pragma once
// What the debrief screen says after the case's end or its critical error, as plain text (no
// Qt): the outcome, what went wrong (case_outcome.h's reasons, in time order of their kind),
// and the metrics as caption/value rows. The widget (debrief_screen.h) only lays it out.

#include <string>
#include <utility>
#include <vector>

#include "app/calot/calot_metrics.h"

namespace vesica::app::calot {

struct DebriefText {
  std::string title;                 // "Calot's triangle: debrief"
  std::string headline;              // OutcomeHeadline: "Passed", "Failed: bile duct injury", "Failed"
  std::vector<std::string> reasons;  // what went wrong, one sentence each; empty when passed
  std::vector<std::pair<std::string, std::string>> metrics;  // caption, value
};

/// The debrief of the case as it stands.
DebriefText MakeDebriefText(const CalotMetrics& metrics);

}  // namespace vesica::app::calot
