#include "app/session/live_input.h"

namespace vesica::app {

void LiveInput::Set(int instrument, const device::InstrumentInput& input) {
  std::lock_guard lock(mutex_);
  frame_.instruments.at(static_cast<std::size_t>(instrument)) = input;
}

void LiveInput::SetRightTool(physics::InstrumentTool tool) {
  std::lock_guard lock(mutex_);
  frame_.right_tool = tool;
}

device::InputFrame LiveInput::Sample(double time_s) {
  std::lock_guard lock(mutex_);
  device::InputFrame f = frame_;
  f.time_s = time_s;
  return f;
}

}  // namespace vesica::app
