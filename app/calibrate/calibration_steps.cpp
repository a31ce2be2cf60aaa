#include "app/calibrate/calibration_steps.h"

namespace vesica::app::calibrate {

const std::vector<StepInfo>& AllSteps() {
  // typical_s: measured on emulated random arms (docs/calibration.md, timings).
  static const std::vector<StepInfo> steps = {
      {Step::kCurrentOffset, "current offset", nullptr, 0.1, true},
      {Step::kEncoderDirection, "encoder direction", "each joint turns a few degrees under a small current", 1.5, true},
      {Step::kRange, "range", "each joint seeks both hard stops, slowly, and pushes on them lightly", 25.0, true},
      {Step::kIndex, "index", "each joint creeps to its encoder's reference index", 6.0, true},
      {Step::kFriction, "friction", "each joint sweeps across mid-range at three speeds, both ways", 24.0, true},
      {Step::kGravity, "gravity", "pitch holds still at several angles (breakaway up and down)", 15.0, true},
      {Step::kTorqueConstant, "torque constant",
       "each joint holds still at five positions against the reference load fixture, which must be clamped on "
       "(breakaway up and down)",
       40.0, false},
      {Step::kRollOffset, "roll offset", nullptr, 10.0, false},
      {Step::kJawSpan, "jaw span", nullptr, 10.0, false},
      {Step::kPedalTravel, "pedal travel", nullptr, 10.0, false},
  };
  return steps;
}

std::vector<Step> AllStepList() {
  std::vector<Step> steps;
  for (const StepInfo& s : AllSteps())
    if (s.in_whole) steps.push_back(s.step);
  return steps;
}

const StepInfo& InfoOf(Step s) { return AllSteps()[static_cast<std::size_t>(s)]; }

std::optional<Step> StepNamed(const std::string& name) {
  std::string n = name;
  for (char& c : n)
    if (c == '-' || c == '_') c = ' ';
  if (n == "direction") n = "encoder direction";
  if (n == "offset") n = "current offset";
  if (n == "kt") n = "torque constant";
  for (const StepInfo& s : AllSteps())
    if (n == s.name) return s.step;
  return std::nullopt;
}

std::string StepNames() {
  return "current-offset, direction, range, index, friction, gravity, torque-constant, roll-offset, jaw-span, "
         "pedal-travel";
}

bool IsHandStep(Step s) { return s == Step::kRollOffset || s == Step::kJawSpan || s == Step::kPedalTravel; }

}  // namespace vesica::app::calibrate
