#pragma once
// Keyboard and mouse driving of the two instruments (documented in the window's status line
// and docs/user-guide.md): plain logic, no Qt, so it is testable.
//
//   grasper (left hand):  A/D yaw, W/S pitch, Q/E insert/withdraw, Z/C roll, X open/close jaw;
//                         left-button drag yaw/pitch, wheel while dragging insert/withdraw
//   hook (right hand):    J/L yaw, I/K pitch, U/O insert/withdraw, N/, roll, M pedal (cautery);
//                         right-button drag yaw/pitch, wheel while dragging insert/withdraw

#include <cstddef>
#include <string>
#include <vector>

#include "physics/instrument/instrument_pose.h"

namespace vesica::app {

struct KeyboardStep {
  double angle_rad = 0.01;             ///< per key press, yaw/pitch/roll
  double insertion_m = 0.002;          ///< per key press
  double jaw_open_rad = 0.6;           ///< jaw angle when open
  double max_pitch_rad = 1.2;          ///< keeps the shaft away from the abdominal wall plane
  double angle_rad_per_pixel = 0.002;  ///< mouse drag, yaw/pitch
  double insertion_m_per_wheel_notch = 0.002;
};

/// Applies one key (an ASCII character, case-insensitive) to the poses of instruments 0 (left)
/// and 1 (right). Insertion stays in [0, max_insertion_m[i]]. Returns false if the key is not
/// an instrument key. `pedal` toggles with M.
bool ApplyInstrumentKey(char key, std::vector<physics::InstrumentPose>& poses,
                        const std::vector<double>& max_insertion_m, bool& pedal, const KeyboardStep& step = {});

/// A mouse drag of (dx, dy) pixels (x right, y down) on instrument `instrument`: dragging left
/// yaws as A/J do, dragging up pitches as W/I do. Returns false for an instrument that is not there.
bool ApplyInstrumentDrag(std::size_t instrument, double dx_px, double dy_px,
                         std::vector<physics::InstrumentPose>& poses, const KeyboardStep& step = {});

/// `notches` of the mouse wheel (positive: away from the user) insert instrument `instrument`
/// (negative: withdraw), within [0, max_insertion_m[instrument]].
bool ApplyInstrumentWheel(std::size_t instrument, double notches, std::vector<physics::InstrumentPose>& poses,
                          const std::vector<double>& max_insertion_m, const KeyboardStep& step = {});

/// The one-line key summary shown to the user.
std::string KeyboardHelp();

}  // namespace vesica::app
