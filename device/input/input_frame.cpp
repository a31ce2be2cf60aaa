#include "device/input/input_frame.h"

#include <cmath>

namespace vesica::device {

std::optional<std::string> FrameProblem(const InputFrame& frame, const InputFrame* previous) {
  if (!std::isfinite(frame.time_s)) return "time_s is not finite";
  if (previous != nullptr && !(frame.time_s > previous->time_s)) return "time_s is not after the previous frame's";
  static constexpr const char* kSide[2] = {"left", "right"};
  for (int side = 0; side < 2; ++side) {
    const physics::InstrumentPose& p = frame.instruments[side].pose;
    for (double v : {p.yaw_rad, p.pitch_rad, p.roll_rad, p.insertion_m, p.jaw_angle_rad}) {
      if (!std::isfinite(v)) return std::string(kSide[side]) + " instrument has a non-finite value";
    }
    if (p.insertion_m < 0) return std::string(kSide[side]) + "_insertion_m is negative";
  }
  if (!physics::IsRightHandTool(frame.right_tool)) return "the right port holds the grasper";
  return std::nullopt;
}

}  // namespace vesica::device
