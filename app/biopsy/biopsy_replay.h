#pragma once
// A recorded stylus stream run through a biopsy session headless, tick by tick at the haptic
// rate, as vesica-replay does: the same recording gives the same forces and metrics every time.

#include <functional>
#include <memory>
#include <optional>

#include "app/biopsy/biopsy_session.h"
#include "device/stylus/stylus_recording.h"

namespace vesica::app::biopsy {

struct BiopsyReplayResult {
  SessionMetrics metrics;
  physics::BiopsyMetrics needle_metrics;  ///< with the sample's precision band and no-go kinds
  long ticks = 0;
  double duration_s = 0.0;  ///< session time replayed
};

/// Replays `recording` from its first sample's time to its last at `tick_s` (the haptic period);
/// `progress(tick, ticks)` is called every 1,000 ticks when given. Throws std::invalid_argument
/// for an empty recording or a bad tick.
BiopsyReplayResult ReplayBiopsy(std::shared_ptr<const BiopsyPatient> patient, const device::StylusRecording& recording,
                                const BiopsySessionSettings& settings = {}, double tick_s = 0.001,
                                const std::function<void(long, long)>& progress = {});

}  // namespace vesica::app::biopsy
