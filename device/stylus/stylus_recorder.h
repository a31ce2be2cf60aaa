#pragma once

#include "device/stylus/stylus_recording.h"

namespace vesica::device {

/// Records a live stylus stream, one sample per physics step, for WriteStylusRecording and
/// ReplayStylus (or vesica-omnisim --hand recording FILE).
class StylusRecorder {
 public:
  /// Samples must come with strictly increasing time and pass StylusStateProblem
  /// (std::invalid_argument naming the problem otherwise; the recording is left unchanged).
  void Append(double time_s, const StylusState& state);

  const StylusRecording& recording() const { return recording_; }

 private:
  StylusRecording recording_;
};

}  // namespace vesica::device
