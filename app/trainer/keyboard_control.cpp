#include "app/trainer/keyboard_control.h"

#include <algorithm>
#include <cctype>

namespace vesica::app {

namespace {
// The one place where a manual command becomes a pose: insertion and pitch kept in range.
void Nudge(physics::InstrumentPose& pose, double physics::InstrumentPose::*field, double delta, double max_insertion_m,
           const KeyboardStep& step) {
  if (field == &physics::InstrumentPose::insertion_m) {
    pose.insertion_m = std::clamp(pose.insertion_m + delta, 0.0, max_insertion_m);
  } else {
    pose.*field += delta;
    pose.pitch_rad = std::clamp(pose.pitch_rad, -step.max_pitch_rad, step.max_pitch_rad);
  }
}

double MaxInsertion(const std::vector<double>& max_insertion_m, std::size_t instrument) {
  return instrument < max_insertion_m.size() ? max_insertion_m[instrument] : 0.0;
}
}  // namespace

bool ApplyInstrumentKey(char key, std::vector<physics::InstrumentPose>& poses,
                        const std::vector<double>& max_insertion_m, bool& pedal, const KeyboardStep& step) {
  const char k = static_cast<char>(std::tolower(static_cast<unsigned char>(key)));
  struct Binding {
    char key;
    std::size_t instrument;
    double physics::InstrumentPose::*field;
    double sign;
  };
  // A/J move the tip to the picture's left, D/L to its right, W/I up, S/K down.
  static constexpr Binding kBindings[] = {
      {'a', 0, &physics::InstrumentPose::yaw_rad, -1},     {'d', 0, &physics::InstrumentPose::yaw_rad, +1},
      {'w', 0, &physics::InstrumentPose::pitch_rad, +1},   {'s', 0, &physics::InstrumentPose::pitch_rad, -1},
      {'q', 0, &physics::InstrumentPose::insertion_m, +1}, {'e', 0, &physics::InstrumentPose::insertion_m, -1},
      {'z', 0, &physics::InstrumentPose::roll_rad, +1},    {'c', 0, &physics::InstrumentPose::roll_rad, -1},
      {'j', 1, &physics::InstrumentPose::yaw_rad, -1},     {'l', 1, &physics::InstrumentPose::yaw_rad, +1},
      {'i', 1, &physics::InstrumentPose::pitch_rad, +1},   {'k', 1, &physics::InstrumentPose::pitch_rad, -1},
      {'u', 1, &physics::InstrumentPose::insertion_m, +1}, {'o', 1, &physics::InstrumentPose::insertion_m, -1},
      {'n', 1, &physics::InstrumentPose::roll_rad, +1},    {',', 1, &physics::InstrumentPose::roll_rad, -1},
  };
  if (k == 'm') {
    pedal = !pedal;
    return true;
  }
  if (k == 'x' || k == 'b') {  // the grasper's jaw; the right hand's (clip applier, scissors)
    const std::size_t instrument = k == 'x' ? 0 : 1;
    if (instrument >= poses.size()) return false;
    poses[instrument].jaw_angle_rad = poses[instrument].jaw_angle_rad > 0 ? 0.0 : step.jaw_open_rad;
    return true;
  }
  for (const auto& b : kBindings) {
    if (b.key != k) continue;
    if (b.instrument >= poses.size()) return false;
    const bool insertion = b.field == &physics::InstrumentPose::insertion_m;
    Nudge(poses[b.instrument], b.field, b.sign * (insertion ? step.insertion_m : step.angle_rad),
          MaxInsertion(max_insertion_m, b.instrument), step);
    return true;
  }
  return false;
}

bool ApplyInstrumentDrag(std::size_t instrument, double dx_px, double dy_px,
                         std::vector<physics::InstrumentPose>& poses, const KeyboardStep& step) {
  if (instrument >= poses.size()) return false;
  // Yaw turns the shaft about the cranial axis: from the umbilical scope, + yaw carries the tip
  // toward the patient's left, the picture's right (tests/field: the tip follows the hand).
  Nudge(poses[instrument], &physics::InstrumentPose::yaw_rad, dx_px * step.angle_rad_per_pixel, 0.0, step);
  Nudge(poses[instrument], &physics::InstrumentPose::pitch_rad, -dy_px * step.angle_rad_per_pixel, 0.0, step);
  return true;
}

bool ApplyInstrumentWheel(std::size_t instrument, double notches, std::vector<physics::InstrumentPose>& poses,
                          const std::vector<double>& max_insertion_m, const KeyboardStep& step) {
  if (instrument >= poses.size()) return false;
  Nudge(poses[instrument], &physics::InstrumentPose::insertion_m, notches * step.insertion_m_per_wheel_notch,
        MaxInsertion(max_insertion_m, instrument), step);
  return true;
}

std::string KeyboardHelp() {
  return "Grasper: A/D yaw, W/S pitch, Q/E in/out, Z/C roll, X jaw, left drag (+wheel)   |   Hook: J/L yaw, I/K "
         "pitch, U/O in/out, N/, roll, M pedal, B jaw, T exchange tool, right drag (+wheel)";
}

}  // namespace vesica::app
