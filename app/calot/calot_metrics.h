#pragma once
// The Calot's triangle metrics of one session, fed the snapshots in time order: when the
// critical view of safety was first reached and whether that was before the first clip, each
// structure's clips and cuts (judged against its planned cut point), bleeding, bile leaks, and
// the critical error: a clip or cut on the common bile or common hepatic duct (bile duct
// injury), which ends the case.
//
// Events in a snapshot happened during the step that led to it, so they are judged against the
// state before that step: a clip placed in the same step that completes the view came before it.

#include <optional>
#include <string>
#include <vector>

#include "app/calot/calot_snapshot.h"
#include "app/calot/cvs_assessment.h"

namespace vesica::app::calot {

struct PlacedClip {
  double s = 0;       // material coordinate, 0 (patient's side) .. 1
  double time_s = 0;  // session time
};

struct StructureCut {
  double s = 0;
  double time_s = 0;
  bool patient_side_clipped = false;      // a clip between the cut and the patient's end (s below the cut)
  bool gallbladder_side_clipped = false;  // a clip between the cut and the gallbladder's end (s above the cut)

  bool BetweenClips() const { return patient_side_clipped && gallbladder_side_clipped; }
};

/// One structure over the session.
struct StructureHistory {
  StructureKind kind = StructureKind::kCysticDuct;
  std::string name{};
  double planned_cut_s = 0.5;
  std::vector<PlacedClip> clips{};
  std::vector<StructureCut> cuts{};

  /// Clips below (patient's side of) and above (gallbladder's side of) the planned cut point.
  int ClipsOnPatientSide() const;
  int ClipsOnGallbladderSide() const;
  /// At least two clips on the patient's side of the planned cut point and one on the gallbladder's.
  bool ClipsPlacedCorrectly() const;
  bool Divided() const { return !cuts.empty(); }
  /// Divided, and every cut had a clip on either side when it was made.
  bool DividedBetweenClips() const;
};

enum class FindingKind {
  kClipBeforeCriticalView,  // a clip on a cystic structure before the critical view of safety
  kCutBeforeCriticalView,   // a cut on a cystic structure before it
  kBileDuctInjury,          // a clip or cut on the common bile or common hepatic duct: ends the case
  kBleeding,                // the artery cut with no clip on its patient's side, or the model reports bleeding
  kBileLeak,                // the cystic duct cut with an end open, or the model reports bile leaking
};

/// One thing that went wrong, when and where.
struct Finding {
  FindingKind kind = FindingKind::kBleeding;
  int structure = 0;                             // index into the snapshots' structures
  CalotEventKind action = CalotEventKind::kCut;  // what caused it (for a model-reported leak: kCut)
  std::optional<double> s{};  // where on the structure; none when the model reported it without a cut
  double time_s = 0;
  bool before_critical_view = false;  // the critical view of safety had not been reached yet
};

class CalotMetrics {
 public:
  /// Throws CalotInputError for thresholds outside 0..1.
  explicit CalotMetrics(const CvsThresholds& thresholds = {});

  /// Takes the next snapshot. Throws CalotInputError (ValidateSnapshot) for a bad one, or for a
  /// structure list that differs from the first snapshot's in size or kinds. After a bile duct
  /// injury the case has ended: later snapshots (and later events of the same one) are ignored.
  void Observe(const CalotSnapshot& snapshot);

  /// A bile duct injury ended the case.
  bool CaseEnded() const { return case_ended_; }

  /// When the critical view of safety was first reached; none when it never was.
  std::optional<double> CriticalViewTime() const { return critical_view_time_s_; }
  /// When the first clip was placed on any structure; none when none was.
  std::optional<double> FirstClipTime() const { return first_clip_time_s_; }
  /// The critical view was reached, and before any clip was placed (true when it was reached and
  /// no clip has been placed yet).
  bool CriticalViewBeforeFirstClip() const;

  /// The assessment of the latest snapshot.
  const CvsAssessment& LatestAssessment() const { return latest_; }
  double time_s() const { return time_s_; }
  bool observed() const { return observed_; }

  const std::vector<StructureHistory>& Structures() const { return structures_; }
  /// What went wrong, in time order.
  const std::vector<Finding>& Findings() const { return findings_; }
  int Count(FindingKind kind) const;

  /// Clips on all structures of this kind.
  int ClipsOn(StructureKind kind) const;
  /// Every structure of this kind divided between clips (false when there is none).
  bool AllDividedBetweenClips(StructureKind kind) const;
  /// Every structure of this kind with its clips placed correctly (false when there is none).
  bool AllClipsPlacedCorrectly(StructureKind kind) const;

 private:
  void TakeStructures(const CalotSnapshot& snapshot);
  void ApplyEvent(const CalotEvent& event);
  void ApplyModelLeaks(const CalotSnapshot& snapshot);

  CvsThresholds thresholds_;
  bool observed_ = false;
  double time_s_ = 0;
  bool case_ended_ = false;
  CvsAssessment latest_{};
  std::optional<double> critical_view_time_s_;
  std::optional<double> first_clip_time_s_;
  bool first_clip_before_view_ = false;
  std::vector<StructureHistory> structures_;
  std::vector<Finding> findings_;
  // Per structure, for bleeding and for bile: what the model reported in the latest snapshot, and
  // whether the bleed (leak) going on now is already counted (by its cut or by the model's flag),
  // so the model's flag for a bleed its cut already counted is not counted again.
  struct ModelFlag {
    bool reported = false;
    bool counted = false;
  };
  std::vector<ModelFlag> bleeding_;
  std::vector<ModelFlag> leaking_;
};

}  // namespace vesica::app::calot
