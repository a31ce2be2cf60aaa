#pragma once
// The case's outcome from its metrics: passed, or failed with each reason in words a trainee
// reads in the debrief ("Clip placed on the common bile duct at 12.4 s before the critical view
// of safety: bile duct injury"). A case passes when the critical view of safety came before the
// first clip, the cystic duct and artery each have two clips on the patient's side of their
// planned cut point and one on the gallbladder's and are divided between clips, and nothing
// bled, leaked or injured a bile duct.

#include <string>
#include <vector>

#include "app/calot/calot_metrics.h"

namespace vesica::app::calot {

enum class ReasonKind {
  kBileDuctInjury,           // the critical error
  kActedBeforeCriticalView,  // a clip or cut before the critical view of safety
  kCriticalViewNotReached,   // never reached (and nothing done before it)
  kBleeding,
  kBileLeak,
  kClipsMisplaced,
  kNotDivided,
  kNotDividedBetweenClips,
};

struct CaseReason {
  ReasonKind kind = ReasonKind::kBileDuctInjury;
  std::string text{};  // one sentence, no full stop
};

struct CaseOutcome {
  bool passed = false;
  bool critical_error = false;        // a bile duct injury ended the case
  std::vector<CaseReason> reasons{};  // empty when passed; the critical error first
};

/// Judges the case as it stands (call it at the case's end or after the critical error).
CaseOutcome JudgeCase(const CalotMetrics& metrics);

/// "Passed", "Failed: bile duct injury" or "Failed".
std::string OutcomeHeadline(const CaseOutcome& outcome);

/// "12.4 s": a session time as the debrief writes it.
std::string FormatEventTime(double time_s);

}  // namespace vesica::app::calot
