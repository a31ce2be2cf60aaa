#pragma once
// Where vesica-omnisim's scripted hand means to hold the stylus at each time: a built-in needle
// biopsy (approach, insert, hold, withdraw) or a stylus recording (docs/omni.md), repeating.

#include <memory>

#include "device/stylus/replay_stylus.h"
#include "device/stylus/stylus_recording.h"

namespace vesica::app {

/// The built-in biopsy motion, in the Omni's frame (m): from a point 40 mm above the entry the
/// hand approaches the entry along the needle's line D (tilted 30 degrees from vertical toward
/// the user) for 1 s, inserts 50 mm along D for 2 s, holds 1 s with button 1 pressed for the
/// middle 0.2 s (the biopsy), withdraws for 2 s and rests 0.5 s: 6.5 s a cycle.
struct BuiltInBiopsyMotion {
  Eigen::Vector3d entry_m{0.0, 0.0, 0.0};
  double approach_m = 0.040;
  double insertion_m = 0.050;
  double tilt_rad = 0.5235987755982988;  // 30 degrees
};

/// The built-in motion as a recording sampled every 10 ms (ReplayStylus interpolates between).
device::StylusRecording BuiltInBiopsyRecording(const BuiltInBiopsyMotion& motion = {});

/// A hand script from a recording, played from its first sample's time and repeated.
class HandScript {
 public:
  /// std::invalid_argument as ReplayStylus's.
  explicit HandScript(device::StylusRecording recording);
  /// The intended stylus state t seconds after the start (t >= 0; loops over the recording).
  device::StylusState At(double t_s) const;
  double period_s() const { return period_s_; }
  /// The recording it plays (directions unit).
  const device::StylusRecording& Recording() const { return replay_.recording(); }

 private:
  device::ReplayStylus replay_;
  double period_s_;
};

}  // namespace vesica::app
