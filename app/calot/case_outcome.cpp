#include "app/calot/case_outcome.h"

#include <cctype>
#include <cstdio>

namespace vesica::app::calot {
namespace {

std::string Capitalised(std::string text) {
  if (!text.empty()) text[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(text[0])));
  return text;
}

std::string Action(const Finding& f, const std::string& structure) {
  return std::string(f.action == CalotEventKind::kClip ? "Clip placed on the " : "Cut made through the ") + structure +
         " at " + FormatEventTime(f.time_s);
}

std::string Plural(int count, const char* one, const char* many) {
  return std::to_string(count) + " " + (count == 1 ? one : many);
}

std::string MissingCriteria(const CvsAssessment& a) {
  std::string missing;
  const auto add = [&](const std::string& part) { missing += (missing.empty() ? "" : "; ") + part; };
  if (!a.triangle_cleared) add("fat left in the triangle");
  if (!a.lower_third_separated) add("lower third of the gallbladder not separated from the liver bed");
  if (!a.two_structures_seen)
    add(Plural(a.structures_seen_entering, "structure", "structures") + " seen entering the gallbladder, 2 needed");
  return missing;
}

}  // namespace

std::string FormatEventTime(double time_s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f s", time_s);
  return text;
}

CaseOutcome JudgeCase(const CalotMetrics& metrics) {
  CaseOutcome outcome;
  const auto& structures = metrics.Structures();
  const auto add = [&](ReasonKind kind, std::string text) { outcome.reasons.push_back({kind, std::move(text)}); };
  const auto name = [&](int index) { return structures[index].name; };

  for (const Finding& f : metrics.Findings()) {
    if (f.kind != FindingKind::kBileDuctInjury) continue;
    outcome.critical_error = true;
    add(ReasonKind::kBileDuctInjury, Action(f, name(f.structure)) +
                                         (f.before_critical_view ? " before the critical view of safety" : "") +
                                         ": bile duct injury, the case ends");
  }
  // The first clip or cut before the view says what the trainee skipped; more add nothing.
  for (const Finding& f : metrics.Findings()) {
    if (f.kind != FindingKind::kClipBeforeCriticalView && f.kind != FindingKind::kCutBeforeCriticalView) continue;
    add(ReasonKind::kActedBeforeCriticalView, Action(f, name(f.structure)) + " before the critical view of safety");
    break;
  }
  if (!metrics.CriticalViewTime() && !metrics.FirstClipTime() && !outcome.critical_error)
    add(ReasonKind::kCriticalViewNotReached,
        "The critical view of safety was not reached (" + MissingCriteria(metrics.LatestAssessment()) + ")");
  for (const Finding& f : metrics.Findings()) {
    if (f.kind == FindingKind::kBleeding) {
      add(ReasonKind::kBleeding, f.s ? Capitalised(name(f.structure)) + " cut at " + FormatEventTime(f.time_s) +
                                           " with no clip on the patient's side: bleeding"
                                     : "Bleeding from the " + name(f.structure) + " at " + FormatEventTime(f.time_s));
    } else if (f.kind == FindingKind::kBileLeak) {
      add(ReasonKind::kBileLeak,
          f.s ? Capitalised(name(f.structure)) + " cut at " + FormatEventTime(f.time_s) +
                    " not between clips: bile leak"
              : "Bile leaking from the " + name(f.structure) + " at " + FormatEventTime(f.time_s));
    }
  }
  if (!outcome.critical_error) {
    for (const StructureHistory& st : structures) {
      if (!IsCysticStructure(st.kind)) continue;
      if (!st.ClipsPlacedCorrectly()) {
        add(ReasonKind::kClipsMisplaced,
            Capitalised(st.name) + ": " + Plural(st.ClipsOnPatientSide(), "clip", "clips") +
                " on the patient's side of the cut point (2 needed), " + std::to_string(st.ClipsOnGallbladderSide()) +
                " on the gallbladder's side (1 needed)");
      }
      if (!st.Divided()) {
        add(ReasonKind::kNotDivided, Capitalised(st.name) + " not divided");
      } else if (!st.DividedBetweenClips()) {
        add(ReasonKind::kNotDividedBetweenClips, Capitalised(st.name) + " not divided between clips");
      }
    }
  }
  outcome.passed = outcome.reasons.empty();
  return outcome;
}

std::string OutcomeHeadline(const CaseOutcome& outcome) {
  if (outcome.passed) return "Passed";
  return outcome.critical_error ? "Failed: bile duct injury" : "Failed";
}

}  // namespace vesica::app::calot
