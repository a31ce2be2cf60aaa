#pragma once
// Keyboard driving of the two instruments (documented in the window's status line and in
// docs/scenario.md's neighbour, the README): plain logic, no Qt, so it is testable.
//
//   grasper (left hand):  A/D yaw, W/S pitch, Q/E insert/withdraw, Z/C roll, X open/close jaw
//   hook (right hand):    J/L yaw, I/K pitch, U/O insert/withdraw, N/, roll, M pedal (cautery)

#include <string>
#include <vector>

#include "physics/instrument/instrument_pose.h"

namespace vesica::app {

struct KeyboardStep {
  double angle_rad = 0.01;     ///< per key press, yaw/pitch/roll
  double insertion_m = 0.002;  ///< per key press
  double jaw_open_rad = 0.6;   ///< jaw angle when open
  double max_pitch_rad = 1.2;  ///< keeps the shaft away from the abdominal wall plane
};

/// Applies one key (an ASCII character, case-insensitive) to the poses of instruments 0 (left)
/// and 1 (right). Insertion stays in [0, max_insertion_m[i]]. Returns false if the key is not
/// an instrument key. `pedal` toggles with M.
bool ApplyInstrumentKey(char key, std::vector<physics::InstrumentPose>& poses,
                        const std::vector<double>& max_insertion_m, bool& pedal, const KeyboardStep& step = {});

/// The one-line key summary shown to the user.
std::string KeyboardHelp();

}  // namespace vesica::app
