#include "device/input/input_recorder.h"

#include <stdexcept>
#include <utility>

namespace vesica::device {

InputRecorder::InputRecorder(std::string scenario_name) { recording_.scenario_name = std::move(scenario_name); }

void InputRecorder::Append(const InputFrame& frame) {
  const InputFrame* previous = recording_.frames.empty() ? nullptr : &recording_.frames.back();
  if (const auto problem = FrameProblem(frame, previous)) {
    throw std::invalid_argument("InputRecorder: frame " + std::to_string(recording_.frames.size()) + ": " + *problem);
  }
  recording_.frames.push_back(frame);
}

}  // namespace vesica::device
