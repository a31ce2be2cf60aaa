#pragma once

#include <string>

#include "device/input/input_frame.h"

namespace vesica::device {

/// Records what a live session's input source produced, one frame per physics step, so the
/// session can be written with WriteInputRecording and replayed with ReplayInput.
class InputRecorder {
 public:
  explicit InputRecorder(std::string scenario_name = {});

  /// Frames must come with strictly increasing time and finite values, insertion >= 0
  /// (std::invalid_argument otherwise, and the recording is left unchanged).
  void Append(const InputFrame& frame);

  const InputRecording& recording() const { return recording_; }

 private:
  InputRecording recording_;
};

}  // namespace vesica::device
