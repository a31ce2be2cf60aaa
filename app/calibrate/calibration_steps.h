// The calibration's steps in the order they run (the core's procedures, device/calibration), what
// each one moves (for the prompt) and roughly how long it takes on a nominal arm (progress).
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace vesica::app::calibrate {

enum class Step {
  kCurrentOffset,
  kEncoderDirection,
  kRange,
  kIndex,
  kFriction,
  kGravity,
  kTorqueConstant,
  kRollOffset,
  kJawSpan,
  kPedalTravel
};

struct StepInfo {
  Step step;
  const char* name;    ///< as on the command line and in the core's progress ("current offset")
  const char* motion;  ///< what moves, for the prompt; null: nothing moves
  double typical_s;    ///< bus time on the emulated arms, all three joints
  bool in_whole;       ///< part of a whole calibration; false: a check run on its own (--step)
};

const std::vector<StepInfo>& AllSteps();
/// The steps of a whole calibration, in order (not the torque-constant check: it needs the
/// reference load fixture clamped on, and runs on its own).
std::vector<Step> AllStepList();
const StepInfo& InfoOf(Step s);
/// "current-offset" or "current offset", "direction", "range", "index", "friction", "gravity",
/// "torque-constant", "roll-offset", "jaw-span", "pedal-travel".
std::optional<Step> StepNamed(const std::string& name);
/// The names a user may type, for messages.
std::string StepNames();
/// A guided hand step (a person moves the roll, the jaw handle or the pedal).
bool IsHandStep(Step s);

}  // namespace vesica::app::calibrate
