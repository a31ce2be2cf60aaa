#pragma once
// Scripted Calot's triangle sessions for the training-logic tests: the anatomical variants of
// issue 36 as plain snapshots (what the trainer would copy from the physics), and a script that
// dissects, clips and cuts them step by step.

#include <vector>

#include "app/calot/calot_snapshot.h"

namespace vesica::app::calot::testing {

enum class Variant {
  kStandard,               // cystic duct and artery of ordinary length
  kShortCysticDuct,        // little room between the common duct and the gallbladder: cut point near the neck
  kLowInsertion,           // the cystic duct runs beside the common bile duct and joins it low
  kArteryCrossingInFront,  // the cystic artery crosses in front of the common hepatic duct
};

inline constexpr Variant kAllVariants[] = {Variant::kStandard, Variant::kShortCysticDuct, Variant::kLowInsertion,
                                           Variant::kArteryCrossingInFront};

const char* VariantName(Variant variant);

/// Indices of the structures in every variant's list.
inline constexpr int kCysticDuct = 0;
inline constexpr int kCysticArtery = 1;
inline constexpr int kCommonHepaticDuct = 2;
inline constexpr int kCommonBileDuct = 3;

/// The variant's structures before any dissection: fat over everything (nothing visible), the
/// cystic duct and artery entering the gallbladder, each with its planned cut point.
std::vector<StructureState> VariantStructures(Variant variant);

/// A session being scripted: change the state, then Advance to emit the next snapshot (whose
/// events are those done since the previous one, stamped with the new snapshot's time).
class ScriptedCase {
 public:
  explicit ScriptedCase(Variant variant = Variant::kStandard);

  /// Emits the state as a snapshot dt_s later.
  void Advance(double dt_s);

  /// Dissection state: fractions of the fat layer removed and of the lower third separated.
  void SetDissection(double fat_removed_fraction, double lower_third_separated_fraction);
  /// The fraction of each structure in view (fat cleared off it).
  void SetVisible(int structure, double visible_fraction);
  /// The cystic duct and artery in full view (0.9 of their length).
  void ExposeCysticStructures();
  /// All three criteria met, then one step: the critical view of safety.
  void ReachCriticalView();

  void Clip(int structure, double s);
  void Cut(int structure, double s);
  void SetBleeding(int structure, bool bleeding);
  void SetBileLeaking(int structure, bool leaking);

  /// Two clips on the patient's side of the planned cut point, one on the gallbladder's side,
  /// a cut between them: for one structure, a step after each action.
  void ClipAndDivideCorrectly(int structure);

  double planned_cut_s(int structure) const { return state_.structures[structure].planned_cut_s; }
  double time_s() const { return state_.time_s; }
  const std::vector<CalotSnapshot>& snapshots() const { return snapshots_; }

 private:
  CalotSnapshot state_;  // events: pending until the next Advance
  std::vector<CalotSnapshot> snapshots_;
};

/// The whole correct case: dissection to the critical view, then the artery and the duct
/// clipped and divided between clips.
ScriptedCase CorrectDissection(Variant variant);

}  // namespace vesica::app::calot::testing
