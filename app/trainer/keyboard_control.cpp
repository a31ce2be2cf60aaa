#include "app/trainer/keyboard_control.h"

#include <algorithm>
#include <cctype>

namespace vesica::app {

bool ApplyInstrumentKey(char key, std::vector<physics::InstrumentPose>& poses,
                        const std::vector<double>& max_insertion_m, bool& pedal, const KeyboardStep& step) {
  const char k = static_cast<char>(std::tolower(static_cast<unsigned char>(key)));
  struct Binding {
    char key;
    std::size_t instrument;
    double physics::InstrumentPose::*field;
    double sign;
  };
  static constexpr Binding kBindings[] = {
      {'a', 0, &physics::InstrumentPose::yaw_rad, +1},     {'d', 0, &physics::InstrumentPose::yaw_rad, -1},
      {'w', 0, &physics::InstrumentPose::pitch_rad, +1},   {'s', 0, &physics::InstrumentPose::pitch_rad, -1},
      {'q', 0, &physics::InstrumentPose::insertion_m, +1}, {'e', 0, &physics::InstrumentPose::insertion_m, -1},
      {'z', 0, &physics::InstrumentPose::roll_rad, +1},    {'c', 0, &physics::InstrumentPose::roll_rad, -1},
      {'j', 1, &physics::InstrumentPose::yaw_rad, +1},     {'l', 1, &physics::InstrumentPose::yaw_rad, -1},
      {'i', 1, &physics::InstrumentPose::pitch_rad, +1},   {'k', 1, &physics::InstrumentPose::pitch_rad, -1},
      {'u', 1, &physics::InstrumentPose::insertion_m, +1}, {'o', 1, &physics::InstrumentPose::insertion_m, -1},
      {'n', 1, &physics::InstrumentPose::roll_rad, +1},    {',', 1, &physics::InstrumentPose::roll_rad, -1},
  };
  if (k == 'm') {
    pedal = !pedal;
    return true;
  }
  if (k == 'x') {
    if (poses.empty()) return false;
    poses[0].jaw_angle_rad = poses[0].jaw_angle_rad > 0 ? 0.0 : step.jaw_open_rad;
    return true;
  }
  for (const auto& b : kBindings) {
    if (b.key != k) continue;
    if (b.instrument >= poses.size()) return false;
    auto& pose = poses[b.instrument];
    if (b.field == &physics::InstrumentPose::insertion_m) {
      const double max = b.instrument < max_insertion_m.size() ? max_insertion_m[b.instrument] : 0.0;
      pose.insertion_m = std::clamp(pose.insertion_m + b.sign * step.insertion_m, 0.0, max);
    } else {
      pose.*b.field += b.sign * step.angle_rad;
      pose.pitch_rad = std::clamp(pose.pitch_rad, -step.max_pitch_rad, step.max_pitch_rad);
    }
    return true;
  }
  return false;
}

std::string KeyboardHelp() {
  return "Grasper: A/D yaw, W/S pitch, Q/E in/out, Z/C roll, X jaw   |   Hook: J/L yaw, I/K pitch, U/O in/out, "
         "N/, roll, M pedal";
}

}  // namespace vesica::app
