#include "app/calot/calot_session_metrics.h"

#include "app/calot/case_outcome.h"

namespace vesica::app::calot {

void StoreCalotMetrics(const CalotMetrics& metrics, SessionMetrics& session) {
  session.calot_step = true;
  session.cvs_achieved = metrics.CriticalViewTime().has_value();
  session.cvs_time_s = metrics.CriticalViewTime().value_or(0.0);
  session.cvs_before_first_clip = metrics.CriticalViewBeforeFirstClip();
  session.cystic_duct_clips = metrics.ClipsOn(StructureKind::kCysticDuct);
  session.cystic_artery_clips = metrics.ClipsOn(StructureKind::kCysticArtery);
  session.cystic_duct_clips_correct = metrics.AllClipsPlacedCorrectly(StructureKind::kCysticDuct);
  session.cystic_artery_clips_correct = metrics.AllClipsPlacedCorrectly(StructureKind::kCysticArtery);
  session.cystic_duct_divided_between_clips = metrics.AllDividedBetweenClips(StructureKind::kCysticDuct);
  session.cystic_artery_divided_between_clips = metrics.AllDividedBetweenClips(StructureKind::kCysticArtery);
  session.bleeding_events = metrics.Count(FindingKind::kBleeding);
  session.bile_leaks = metrics.Count(FindingKind::kBileLeak);
  session.bile_duct_injuries = metrics.Count(FindingKind::kBileDuctInjury);
  session.calot_passed = JudgeCase(metrics).passed;
}

}  // namespace vesica::app::calot
