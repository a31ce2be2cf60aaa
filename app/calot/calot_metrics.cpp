#include "app/calot/calot_metrics.h"

#include <algorithm>
#include <cstdio>

namespace vesica::app::calot {

int StructureHistory::ClipsOnPatientSide() const {
  return static_cast<int>(
      std::count_if(clips.begin(), clips.end(), [&](const PlacedClip& c) { return c.s < planned_cut_s; }));
}

int StructureHistory::ClipsOnGallbladderSide() const {
  return static_cast<int>(
      std::count_if(clips.begin(), clips.end(), [&](const PlacedClip& c) { return c.s > planned_cut_s; }));
}

bool StructureHistory::ClipsPlacedCorrectly() const {
  return ClipsOnPatientSide() >= 2 && ClipsOnGallbladderSide() >= 1;
}

bool StructureHistory::DividedBetweenClips() const {
  return Divided() && std::all_of(cuts.begin(), cuts.end(), [](const StructureCut& cut) { return cut.BetweenClips(); });
}

CalotMetrics::CalotMetrics(const CvsThresholds& thresholds) : thresholds_(thresholds) {
  ValidateThresholds(thresholds);
}

bool CalotMetrics::CriticalViewBeforeFirstClip() const {
  // Not by comparing times: a clip in the step that completes the view has the view's time but
  // came before it.
  return critical_view_time_s_.has_value() && !first_clip_before_view_;
}

int CalotMetrics::Count(FindingKind kind) const {
  return static_cast<int>(
      std::count_if(findings_.begin(), findings_.end(), [&](const Finding& f) { return f.kind == kind; }));
}

int CalotMetrics::ClipsOn(StructureKind kind) const {
  int clips = 0;
  for (const StructureHistory& s : structures_)
    if (s.kind == kind) clips += static_cast<int>(s.clips.size());
  return clips;
}

bool CalotMetrics::AllDividedBetweenClips(StructureKind kind) const {
  bool any = false;
  for (const StructureHistory& s : structures_) {
    if (s.kind != kind) continue;
    any = true;
    if (!s.DividedBetweenClips()) return false;
  }
  return any;
}

bool CalotMetrics::AllClipsPlacedCorrectly(StructureKind kind) const {
  bool any = false;
  for (const StructureHistory& s : structures_) {
    if (s.kind != kind) continue;
    any = true;
    if (!s.ClipsPlacedCorrectly()) return false;
  }
  return any;
}

void CalotMetrics::TakeStructures(const CalotSnapshot& snapshot) {
  if (!observed_) {
    for (const StructureState& st : snapshot.structures)
      structures_.push_back({.kind = st.kind, .name = DisplayName(st), .planned_cut_s = st.planned_cut_s});
    bleeding_.assign(structures_.size(), {});
    leaking_.assign(structures_.size(), {});
    return;
  }
  const auto changed = [&](const std::string& what) {
    char time_text[48];
    std::snprintf(time_text, sizeof time_text, "%.3f", snapshot.time_s);
    throw CalotInputError(std::string("Calot snapshot at t = ") + time_text + " s: " + what +
                          " differs from the first snapshot's (the structures must stay the same, in order)");
  };
  if (snapshot.structures.size() != structures_.size()) changed("the number of structures");
  for (std::size_t i = 0; i < structures_.size(); ++i)
    if (snapshot.structures[i].kind != structures_[i].kind) changed("structures[" + std::to_string(i) + "]'s kind");
}

void CalotMetrics::ApplyEvent(const CalotEvent& event) {
  StructureHistory& st = structures_[event.structure];
  const bool before_view = !critical_view_time_s_.has_value();
  const auto find = [&](FindingKind kind) {
    findings_.push_back({.kind = kind,
                         .structure = event.structure,
                         .action = event.kind,
                         .s = event.s,
                         .time_s = event.time_s,
                         .before_critical_view = before_view});
  };
  if (event.kind == CalotEventKind::kClip) {
    st.clips.push_back({.s = event.s, .time_s = event.time_s});
    if (!first_clip_time_s_) {
      first_clip_time_s_ = event.time_s;
      first_clip_before_view_ = before_view;
    }
  } else {
    StructureCut cut{.s = event.s, .time_s = event.time_s};
    for (const PlacedClip& clip : st.clips) {
      if (clip.s < event.s) cut.patient_side_clipped = true;
      if (clip.s > event.s) cut.gallbladder_side_clipped = true;
    }
    st.cuts.push_back(cut);
    if (!IsMainBileDuct(st.kind)) {
      // Blood comes from the hepatic artery's side only; bile from the common duct and from the
      // gallbladder, so a duct cut leaks from whichever end is open.
      if (CarriesBlood(st.kind) && !cut.patient_side_clipped) {
        find(FindingKind::kBleeding);
        bleeding_[event.structure].counted = true;
      } else if (!CarriesBlood(st.kind) && !cut.BetweenClips()) {
        find(FindingKind::kBileLeak);
        leaking_[event.structure].counted = true;
      }
    }
  }
  if (IsMainBileDuct(st.kind)) {
    find(FindingKind::kBileDuctInjury);
    case_ended_ = true;
  } else if (before_view) {
    find(event.kind == CalotEventKind::kClip ? FindingKind::kClipBeforeCriticalView
                                             : FindingKind::kCutBeforeCriticalView);
  }
}

void CalotMetrics::ApplyModelLeaks(const CalotSnapshot& snapshot) {
  const bool before_view = !critical_view_time_s_.has_value();
  for (std::size_t i = 0; i < snapshot.structures.size(); ++i) {
    const StructureState& st = snapshot.structures[i];
    // A rising flag is a new bleed (leak) unless a cut already counted it; a falling flag ends it.
    const auto follow = [&](bool flag, ModelFlag& state, FindingKind kind) {
      if (flag && !state.reported && !state.counted) {
        findings_.push_back({.kind = kind,
                             .structure = static_cast<int>(i),
                             .action = CalotEventKind::kCut,
                             .s = std::nullopt,
                             .time_s = snapshot.time_s,
                             .before_critical_view = before_view});
        state.counted = true;
      }
      if (!flag && state.reported) state.counted = false;
      state.reported = flag;
    };
    follow(st.bleeding, bleeding_[i], FindingKind::kBleeding);
    follow(st.bile_leaking, leaking_[i], FindingKind::kBileLeak);
  }
}

void CalotMetrics::Observe(const CalotSnapshot& snapshot) {
  if (case_ended_) return;
  ValidateSnapshot(snapshot, observed_ ? time_s_ : 0.0);
  TakeStructures(snapshot);
  observed_ = true;
  time_s_ = snapshot.time_s;
  for (const CalotEvent& event : snapshot.events) {
    ApplyEvent(event);
    if (case_ended_) return;
  }
  ApplyModelLeaks(snapshot);
  latest_ = AssessCriticalView(snapshot, thresholds_);
  if (latest_.Achieved() && !critical_view_time_s_) critical_view_time_s_ = snapshot.time_s;
}

}  // namespace vesica::app::calot
