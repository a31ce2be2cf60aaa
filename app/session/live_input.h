#pragma once
// The instruments' input as the GUI sets it (keyboard and mouse): the GUI thread writes, the
// physics and haptic threads sample. Thread-safe; Sample never blocks for long (a short lock).

#include <mutex>

#include "device/input/instrument_input_source.h"

namespace vesica::app {

class LiveInput final : public device::InstrumentInputSource {
 public:
  explicit LiveInput(const device::InputFrame& initial = {}) : frame_(initial) {}
  void Set(int instrument, const device::InstrumentInput& input);
  /// The tool the right hand's port holds from the next sample on.
  void SetRightTool(physics::InstrumentTool tool);
  device::InputFrame Sample(double time_s) override;

 private:
  std::mutex mutex_;
  device::InputFrame frame_;
};

}  // namespace vesica::app
