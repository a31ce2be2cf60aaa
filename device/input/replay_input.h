#pragma once

#include <cstddef>

#include "device/input/input_frame.h"
#include "device/input/instrument_input_source.h"

namespace vesica::device {

/// Replays a recording. Continuous channels (yaw, pitch, roll, insertion, jaw) are linearly
/// interpolated between the frames around t (no angle wrapping: recordings store roll unwrapped);
/// pedals hold the value of the frame at or before t. Before the first frame it gives the first
/// frame, after the last the last. The returned frame's time_s is the t asked for. Sample is a
/// pure function of t (the cached position only speeds up forward playback), so a replay is
/// deterministic whatever order it is sampled in.
class ReplayInput final : public InstrumentInputSource {
 public:
  /// Throws std::invalid_argument for an empty recording or one with a FrameProblem.
  explicit ReplayInput(InputRecording recording);

  /// t must not be NaN (std::invalid_argument).
  InputFrame Sample(double time_s) override;

  /// Last frame's time minus first frame's (s); 0 for a single frame.
  double duration_s() const;
  double start_time_s() const { return recording_.frames.front().time_s; }
  double end_time_s() const { return recording_.frames.back().time_s; }
  /// True once t is past the last frame's time.
  bool finished(double time_s) const { return time_s > end_time_s(); }

  const InputRecording& recording() const { return recording_; }

 private:
  InputRecording recording_;
  std::size_t cursor_ = 0;  // index of the frame at or before the last sampled t
};

}  // namespace vesica::device
