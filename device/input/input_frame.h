#pragma once
// One sample of both instruments' input, and a recorded sequence of them. Plain data shared by
// the keyboard, replay and CAN arm sources and the physics step that reads them.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "physics/instrument/instrument_pose.h"
#include "physics/instrument/instrument_tool.h"

namespace vesica::device {

/// One instrument's input: its 4-DOF pose about the trocar plus jaw angle, and its foot pedal
/// (the cautery pedal for the hook; unused but recorded for the others).
struct InstrumentInput {
  physics::InstrumentPose pose;
  bool pedal = false;
};

/// Index into InputFrame::instruments.
inline constexpr int kLeft = 0;   // grasper, left hand
inline constexpr int kRight = 1;  // cautery hook, right hand

/// Both instruments at one time (s, session clock).
struct InputFrame {
  double time_s = 0;
  std::array<InstrumentInput, 2> instruments;
  /// What the right hand's port holds (exchanged during a case); the left port keeps the grasper.
  physics::InstrumentTool right_tool = physics::InstrumentTool::kCauteryHook;
};

/// A recorded session: frames strictly increasing in time_s, all values finite, insertion_m >= 0.
struct InputRecording {
  std::string scenario_name;  // may be empty; no line breaks
  std::vector<InputFrame> frames;
};

/// What is wrong with `frame` as the frame after `previous` (nullptr: the first frame) in a
/// recording, or nullopt when it is fine: non-finite values, negative insertion, time not after
/// the previous frame's, the grasper in the right port. The writer, recorder and replay use it to check input at the door.
std::optional<std::string> FrameProblem(const InputFrame& frame, const InputFrame* previous);

}  // namespace vesica::device
