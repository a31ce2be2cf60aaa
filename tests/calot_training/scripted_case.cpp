#include "tests/calot_training/scripted_case.h"

namespace vesica::app::calot::testing {

const char* VariantName(Variant variant) {
  switch (variant) {
    case Variant::kStandard:
      return "standard";
    case Variant::kShortCysticDuct:
      return "short_cystic_duct";
    case Variant::kLowInsertion:
      return "low_insertion";
    case Variant::kArteryCrossingInFront:
      return "artery_crossing_in_front";
  }
  return "?";
}

std::vector<StructureState> VariantStructures(Variant variant) {
  StructureState duct{.kind = StructureKind::kCysticDuct, .name = "cystic duct", .planned_cut_s = 0.6};
  StructureState artery{.kind = StructureKind::kCysticArtery, .name = "cystic artery", .planned_cut_s = 0.55};
  StructureState hepatic{.kind = StructureKind::kCommonHepaticDuct, .name = "common hepatic duct"};
  StructureState bile{.kind = StructureKind::kCommonBileDuct, .name = "common bile duct"};
  duct.enters_gallbladder = true;
  artery.enters_gallbladder = true;
  switch (variant) {
    case Variant::kStandard:
      break;
    case Variant::kShortCysticDuct:
      duct.planned_cut_s = 0.75;  // stump room is on the patient's side: the cut goes near the neck
      break;
    case Variant::kLowInsertion:
      duct.name = "low-inserting cystic duct";
      duct.planned_cut_s = 0.8;  // its lower part lies against the common bile duct
      break;
    case Variant::kArteryCrossingInFront:
      artery.name = "cystic artery (anterior to the common hepatic duct)";
      artery.planned_cut_s = 0.65;
      break;
  }
  return {duct, artery, hepatic, bile};
}

ScriptedCase::ScriptedCase(Variant variant) { state_.structures = VariantStructures(variant); }

void ScriptedCase::Advance(double dt_s) {
  state_.time_s += dt_s;
  for (CalotEvent& event : state_.events) event.time_s = state_.time_s;
  snapshots_.push_back(state_);
  state_.events.clear();
}

void ScriptedCase::SetDissection(double fat_removed_fraction, double lower_third_separated_fraction) {
  state_.fat_removed_fraction = fat_removed_fraction;
  state_.lower_third_separated_fraction = lower_third_separated_fraction;
}

void ScriptedCase::SetVisible(int structure, double visible_fraction) {
  state_.structures[structure].visible_fraction = visible_fraction;
}

void ScriptedCase::ExposeCysticStructures() {
  SetVisible(kCysticDuct, 0.9);
  SetVisible(kCysticArtery, 0.9);
}

void ScriptedCase::ReachCriticalView() {
  SetDissection(0.95, 1.0);
  ExposeCysticStructures();
  Advance(0.5);
}

void ScriptedCase::Clip(int structure, double s) {
  state_.structures[structure].clips_s.push_back(s);
  state_.events.push_back({.kind = CalotEventKind::kClip, .structure = structure, .s = s});
}

void ScriptedCase::Cut(int structure, double s) {
  state_.structures[structure].cuts_s.push_back(s);
  state_.events.push_back({.kind = CalotEventKind::kCut, .structure = structure, .s = s});
}

void ScriptedCase::SetBleeding(int structure, bool bleeding) { state_.structures[structure].bleeding = bleeding; }

void ScriptedCase::SetBileLeaking(int structure, bool leaking) { state_.structures[structure].bile_leaking = leaking; }

void ScriptedCase::ClipAndDivideCorrectly(int structure) {
  const double cut = planned_cut_s(structure);
  Clip(structure, cut - 0.2);
  Advance(2.0);
  Clip(structure, cut - 0.1);
  Advance(2.0);
  Clip(structure, cut + 0.1);
  Advance(2.0);
  Cut(structure, cut);
  Advance(2.0);
}

ScriptedCase CorrectDissection(Variant variant) {
  ScriptedCase script(variant);
  // Fat taken down over a minute; the structures appear as it goes.
  for (int step = 1; step <= 6; ++step) {
    script.SetDissection(0.15 * step, 0.1 * step);
    script.SetVisible(kCysticDuct, 0.12 * step);
    script.SetVisible(kCysticArtery, 0.1 * step);
    script.Advance(10.0);
  }
  script.ReachCriticalView();
  script.ClipAndDivideCorrectly(kCysticArtery);
  script.ClipAndDivideCorrectly(kCysticDuct);
  return script;
}

}  // namespace vesica::app::calot::testing
