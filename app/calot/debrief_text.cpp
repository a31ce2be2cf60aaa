#include "app/calot/debrief_text.h"

#include "app/calot/case_outcome.h"

namespace vesica::app::calot {
namespace {

std::string CriticalView(const CalotMetrics& m) {
  if (!m.CriticalViewTime()) return "not reached";
  std::string text = "reached at " + FormatEventTime(*m.CriticalViewTime());
  if (m.FirstClipTime()) text += m.CriticalViewBeforeFirstClip() ? ", before the first clip" : ", after the first clip";
  return text;
}

std::string Clips(const StructureHistory& st) {
  if (IsMainBileDuct(st.kind)) return std::to_string(st.clips.size()) + (st.clips.empty() ? "" : " (bile duct injury)");
  if (st.clips.empty()) return "none";
  return std::to_string(st.clips.size()) + ": " + std::to_string(st.ClipsOnPatientSide()) + " on the patient's side, " +
         std::to_string(st.ClipsOnGallbladderSide()) + " on the gallbladder's side" +
         (st.ClipsPlacedCorrectly() ? "" : " (2 and 1 needed)");
}

std::string Division(const StructureHistory& st) {
  if (!st.Divided()) return "not divided";
  const std::string when = " at " + FormatEventTime(st.cuts.front().time_s);
  return (st.DividedBetweenClips() ? "between clips" : "not between clips") + when;
}

}  // namespace

DebriefText MakeDebriefText(const CalotMetrics& m) {
  DebriefText text;
  text.title = "Calot's triangle: debrief";
  const CaseOutcome outcome = JudgeCase(m);
  text.headline = OutcomeHeadline(outcome);
  for (const CaseReason& reason : outcome.reasons) text.reasons.push_back(reason.text);

  auto& rows = text.metrics;
  rows.emplace_back("Time", FormatEventTime(m.time_s()));
  rows.emplace_back("Critical view of safety", CriticalView(m));
  for (const StructureHistory& st : m.Structures()) {
    // The common ducts appear only when something was done to them.
    if (IsMainBileDuct(st.kind) && st.clips.empty() && st.cuts.empty()) continue;
    rows.emplace_back("Clips, " + st.name, Clips(st));
    if (IsCysticStructure(st.kind)) rows.emplace_back("Division, " + st.name, Division(st));
    if (IsMainBileDuct(st.kind) && !st.cuts.empty())
      rows.emplace_back("Cuts, " + st.name, std::to_string(st.cuts.size()) + " (bile duct injury)");
  }
  rows.emplace_back("Bleeding events", std::to_string(m.Count(FindingKind::kBleeding)));
  rows.emplace_back("Bile leaks", std::to_string(m.Count(FindingKind::kBileLeak)));
  rows.emplace_back("Bile duct injuries", std::to_string(m.Count(FindingKind::kBileDuctInjury)));
  return text;
}

}  // namespace vesica::app::calot
