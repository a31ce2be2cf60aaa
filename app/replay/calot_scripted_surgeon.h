#pragma once
// A scripted surgeon for Calot's triangle (issue 36), planned step by step from the live model
// (closed loop), through the session's real input only: instrument poses, jaws, the pedal and the
// right hand's exchanged tool. Nothing is written into the model's state.
//
// The correct dissection: the left grasper takes Hartmann's pouch and retracts it laterally; the
// hook (pedal down in short bursts, bounded tip speed) burns the connective tissue of the lower
// third from the neck up; then (optionally the hook burns the triangle's fat it can reach, and)
// the grasper lets go of the pouch and spreads the fat hiding the cystic duct and artery and the
// rest of the triangle's layer (blunt dissection), until the session's critical view of safety
// holds; the clip applier puts two clips on the patient's side of each structure's planned cut
// and one on the gallbladder's, the scissors divide each between them. Why the grasper: the
// hook's tip pushes a tube out of itself (tip radius 2.5 mm plus the tube's), so a fat cell
// nearer the centreline than that less the burn radius (2 mm) never comes within the hook's
// reach, and the sleeve hugging each tube stays; open jaws straddle a tube without pushing it.
// The grasper's reach is checked against the liver only (the soft gallbladder gives way). The failures share the grasp
// and the instruments' moves: clipping before the critical view, the artery cut with no clip, a clip on the common bile
// duct. Tips move at bounded speed; the jaws, the pedal and the exchange switch only while still.

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "app/session/dissection_session.h"
#include "device/input/input_frame.h"

namespace vesica::app {

enum class CalotScript {
  kCorrectDissection,       ///< critical view, then clip twice + once and divide duct and artery
  kClipBeforeCriticalView,  ///< no dissection: clips and divides the duct and artery at once
  kArteryCutWithoutClips,   ///< no dissection, no clip: the scissors through the cystic artery
  kClipCommonBileDuct,      ///< no dissection: the clip applier on the common bile duct (ends the case)
};

/// "correct", "clip-before-view", "artery-cut-unclipped", "clip-common-bile-duct".
std::string CalotScriptName(CalotScript script);

struct CalotSurgeonSettings {
  double tip_speed_m_per_s = 0.04;   ///< neither tip moves faster, > 0
  double settle_s = 0.5;             ///< hands still while the organs settle under the assistant's hold
  double retraction_m = 0.010;       ///< Hartmann's pouch pulled this far laterally ...
  double retraction_gain_m = 0.01;   ///< ... plus this times the fraction of springs cut
  double max_grasp_force_N = 1.0;    ///< traction eased off above this (a harder pull tears the grasp)
  double cell_burn_timeout_s = 1.5;  ///< give up on a fat cell after this long with the pedal down
  /// The hook burns the triangle's fat it can reach before the grasper lets go of the pouch and
  /// spreads the rest (false: the grasper's blunt dissection takes it all, several times faster:
  /// 30 W removes a 2 mm cell in 0.25 s at best).
  bool hook_burns_fat = false;
  double clip_spacing_m = 0.003;  ///< between clips and from the planned cut (shorter tubes: less)
  double max_session_s = 600.0;   ///< stop (unfinished) after this long
  bool log_progress = false;      ///< one line per simulated 5 s on stderr
  /// The scope's eye (CalotSessionSetup::camera): when set, the hook burns only what it sees.
  std::optional<Eigen::Vector3d> scope_eye_W;
  /// Called after every physics step (tests look at the field at a moment of the dissection).
  std::function<void(const DissectionSession&, const SessionStepReport&)> on_step;
};

/// Drives `session` (which must run Calot's triangle) through `script` until it is done, the case
/// ended or max_session_s passed; returns the input frame of every step (time = session time at
/// the start of the step). Throws std::invalid_argument for a session without a triangle and
/// std::runtime_error when the grasper's port reaches no side of Hartmann's pouch.
std::vector<device::InputFrame> RunScriptedCalot(DissectionSession& session, CalotScript script,
                                                 const CalotSurgeonSettings& settings = {});

}  // namespace vesica::app
