#include "app/calot/calot_snapshot.h"

#include <cmath>
#include <cstdio>

namespace vesica::app::calot {
namespace {

std::string Number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

bool IsFraction(double value) { return std::isfinite(value) && value >= 0 && value <= 1; }

}  // namespace

std::string DisplayName(const StructureState& structure) {
  return structure.name.empty() ? StructureKindName(structure.kind) : structure.name;
}

void ValidateSnapshot(const CalotSnapshot& snapshot, double previous_time_s) {
  char time_text[48];
  std::snprintf(time_text, sizeof time_text, "%.3f", snapshot.time_s);
  const std::string where = std::string("Calot snapshot at t = ") + time_text + " s: ";
  const auto bad = [&](const std::string& what) { throw CalotInputError(where + what); };

  if (!std::isfinite(snapshot.time_s) || snapshot.time_s < 0) bad("time_s must be finite and >= 0");
  if (snapshot.time_s < previous_time_s)
    bad("time_s is before the previous snapshot's " + Number(previous_time_s) + " s (snapshots go in time order)");
  if (!IsFraction(snapshot.fat_removed_fraction))
    bad("fat_removed_fraction = " + Number(snapshot.fat_removed_fraction) + " is outside 0..1");
  if (!IsFraction(snapshot.lower_third_separated_fraction))
    bad("lower_third_separated_fraction = " + Number(snapshot.lower_third_separated_fraction) + " is outside 0..1");

  for (std::size_t i = 0; i < snapshot.structures.size(); ++i) {
    const StructureState& st = snapshot.structures[i];
    const std::string at = "structures[" + std::to_string(i) + "] (" + DisplayName(st) + "): ";
    if (!std::isfinite(st.planned_cut_s) || st.planned_cut_s <= 0 || st.planned_cut_s >= 1)
      bad(at + "planned_cut_s = " + Number(st.planned_cut_s) + " must be strictly between 0 and 1");
    if (!IsFraction(st.visible_fraction))
      bad(at + "visible_fraction = " + Number(st.visible_fraction) + " is outside 0..1");
    for (std::size_t k = 0; k < st.clips_s.size(); ++k)
      if (!IsFraction(st.clips_s[k]))
        bad(at + "clips_s[" + std::to_string(k) + "] = " + Number(st.clips_s[k]) + " is outside 0..1");
    for (std::size_t k = 0; k < st.cuts_s.size(); ++k)
      if (!IsFraction(st.cuts_s[k]))
        bad(at + "cuts_s[" + std::to_string(k) + "] = " + Number(st.cuts_s[k]) + " is outside 0..1");
  }

  double last_event_s = previous_time_s;
  for (std::size_t k = 0; k < snapshot.events.size(); ++k) {
    const CalotEvent& e = snapshot.events[k];
    const std::string at = "events[" + std::to_string(k) + "]: ";
    if (e.structure < 0 || e.structure >= static_cast<int>(snapshot.structures.size()))
      bad(at + "structure " + std::to_string(e.structure) + " is not one of the " +
          std::to_string(snapshot.structures.size()) + " structures");
    if (!IsFraction(e.s)) bad(at + "s = " + Number(e.s) + " is outside 0..1");
    if (!std::isfinite(e.time_s) || e.time_s > snapshot.time_s || e.time_s < last_event_s)
      bad(at + "time_s = " + Number(e.time_s) + " is outside [" + Number(last_event_s) + ", " +
          Number(snapshot.time_s) + "] (events go in time order, within their step)");
    last_event_s = e.time_s;
  }
}

}  // namespace vesica::app::calot
