#pragma once
// What the training logic sees of Calot's triangle at one moment: a plain copy of the model's
// state that the trainer fills from the physics after each step, so the assessment and the
// metrics depend on no physics type and can be driven by scripted snapshots in tests.
//
// Material coordinates s run along a structure from the patient's side (s = 0: the hilum or
// duodenum, where the tube is held) to its other end (s = 1: for the cystic duct and artery the
// gallbladder). A clip or cut keeps its s while the tube moves.

#include <stdexcept>
#include <string>
#include <vector>

#include "app/calot/structure_kind.h"

namespace vesica::app::calot {

/// A snapshot (or a sequence of them) that cannot be right; the message names the field.
class CalotInputError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// One tube of the triangle as the model has it now.
struct StructureState {
  StructureKind kind = StructureKind::kCysticDuct;
  std::string name{};               // as the scenario names it ("cystic duct", "posterior cystic artery")
  double planned_cut_s = 0.5;       // where the plan divides it, 0 < s < 1; clip positions are judged against it
  std::vector<double> clips_s{};    // clips on it now, each 0..1
  std::vector<double> cuts_s{};     // cuts through it so far, each 0..1
  bool bleeding = false;            // the model: blood leaves an open end
  bool bile_leaking = false;        // the model: bile leaves an open end
  bool enters_gallbladder = false;  // the structure ends in the gallbladder (as seen in the dissected field)
  double visible_fraction = 0;      // fraction of its length in the camera's view and not under fat, 0..1
};

enum class CalotEventKind { kClip, kCut };

/// Something the trainee did during the step that led to a snapshot.
struct CalotEvent {
  CalotEventKind kind = CalotEventKind::kClip;
  int structure = 0;  // index into CalotSnapshot::structures
  double s = 0;       // material coordinate of the clip or cut, 0..1
  double time_s = 0;  // session time, within [previous snapshot's time, this snapshot's time]
};

struct CalotSnapshot {
  double time_s = 0;                          // session time, s
  std::vector<StructureState> structures;     // the same structures, in the same order, every step
  double fat_removed_fraction = 0;            // of the triangle's fat-and-fibrous layer, 0..1
  double lower_third_separated_fraction = 0;  // of the gallbladder's lower third, freed from the liver bed, 0..1
  std::vector<CalotEvent> events;             // since the previous snapshot, in time order
};

/// The structure's name for messages: its scenario name, or its kind's name when that is empty.
std::string DisplayName(const StructureState& structure);

/// Throws CalotInputError naming the first bad field ("Calot snapshot at t = 12.400 s:
/// structures[2] (common bile duct): clips_s[1] = 1.3 is outside 0..1"): a non-finite or
/// negative time, a time before `previous_time_s`, fractions outside 0..1, planned_cut_s not
/// strictly inside 0..1, events out of time order, outside [previous_time_s, time_s] or naming
/// no structure.
void ValidateSnapshot(const CalotSnapshot& snapshot, double previous_time_s);

}  // namespace vesica::app::calot
