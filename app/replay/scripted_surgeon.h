#pragma once
// A scripted two-handed dissection, planned step by step from the live scene (closed loop), the
// way the committed demo recording data/recordings/dissection.csv was made. Two plans:
//  - the assistant holds the fundus (the surgeon's view, [assistant_retraction]): the left hand's
//    grasper takes Hartmann's pouch (a sixth to a third of the way from the neck to the fundus,
//    where a straight path from its port meets the surface most squarely) and retracts it
//    laterally, away from the fossa's rim, further as the springs go (inferolaterally where the
//    rim hides the slot from the hook's port, as from the French position's left hypochondrium);
//    the hook burns the membrane from the neck toward the fundus, triangle by triangle, taking
//    only what it reaches without crossing an organ and what the scope sees, in short bursts with
//    the pedal down; once the gallbladder is free it is held a moment in the jaws, then let go;
//  - no assistant (the overview layout): the grasper takes the fundus and retracts it away from
//    the liver; the hook burns spring by spring from the fundus end to the neck.
// Tips move at bounded speed; the jaw and pedal switch only while the tips are still.

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <vector>

#include "app/session/dissection_session.h"
#include "device/input/input_frame.h"

namespace vesica::app {

struct ScriptedSurgeonSettings {
  double tip_speed_m_per_s = 0.04;  ///< neither tip moves faster
  double retraction_m = 0.012;      ///< grasp point pulled this far from the bed at first ...
  double retraction_gain_m = 0.02;  ///< ... plus this times the fraction of springs cut
  double burn_distance_m = 0.0015;  ///< pedal down once the hook tip is this close to its target
  /// Below this fraction of the membrane in the hook's straight reach before the traction, the
  /// slot is hidden from the hook's port by the fossa's rim (the French position): ...
  double hidden_slot_reach_fraction = 0.25;
  double hidden_slot_tilt_deg = 15.0;       ///< ... the traction is this far caudal of lateral ...
  double hidden_slot_retraction_m = 0.025;  ///< ... and pulls this far at first
  /// When the hook reaches none of the membrane left for 1 s, the traction turns caudally by this
  /// much, up to max_traction_tilt_deg, before the grasper takes the gallbladder elsewhere.
  double traction_tilt_step_deg = 15.0;
  double max_traction_tilt_deg = 45.0;
  double spring_timeout_s = 2.0;  ///< give up on a spring after this long, come back later
  double max_session_s = 240.0;   ///< stop (unfinished) after this long
  double release_hold_s = 0.5;    ///< after the release, before the end
  bool log_progress = false;      ///< one line per simulated second on stderr
  /// The scope's tip: when set, the hook burns only membrane the camera sees (surgeon's view).
  std::optional<Eigen::Vector3d> scope_eye_W;
  /// Called after every physics step (tests watch the dissection as it goes).
  std::function<void(const DissectionSession&, const SessionStepReport&)> on_step;
};

/// Drives `session` until the gallbladder is free and released (or max_session_s), returning the
/// input frame of every step (time = session time at the start of the step).
std::vector<device::InputFrame> RunScriptedDissection(DissectionSession& session,
                                                      const ScriptedSurgeonSettings& settings = {});

}  // namespace vesica::app
