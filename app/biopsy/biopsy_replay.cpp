#include "app/biopsy/biopsy_replay.h"

#include <cmath>
#include <stdexcept>

#include "device/stylus/replay_stylus.h"

namespace vesica::app::biopsy {

BiopsyReplayResult ReplayBiopsy(std::shared_ptr<const BiopsyPatient> patient, const device::StylusRecording& recording,
                                const BiopsySessionSettings& settings, double tick_s,
                                const std::function<void(long, long)>& progress) {
  if (!(tick_s > 0.0) || !std::isfinite(tick_s))
    throw std::invalid_argument("biopsy replay: tick must be > 0 s, got " + std::to_string(tick_s));
  const device::ReplayStylus stylus(recording);  // throws for an empty or broken recording
  BiopsySession session(std::move(patient), settings);
  const double start_s = stylus.start_time_s();
  // Ticks on the session's own clock (0 at the recording's first sample), counted, not summed.
  const long ticks = std::lround(std::floor((stylus.end_time_s() - start_s) / tick_s + 1e-9)) + 1;
  for (long k = 0; k < ticks; ++k) {
    const double t = static_cast<double>(k) * tick_s;
    session.Tick(stylus.SampleAt(start_s + t), t);
    if (progress && (k + 1) % 1000 == 0) progress(k + 1, ticks);
  }
  BiopsyReplayResult result;
  result.metrics = session.Metrics();
  result.needle_metrics = session.needle().metrics();
  result.ticks = ticks;
  result.duration_s = static_cast<double>(ticks - 1) * tick_s;
  return result;
}

}  // namespace vesica::app::biopsy
