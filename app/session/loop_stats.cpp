#include "app/session/loop_stats.h"

#include <algorithm>
#include <cmath>

namespace vesica::app {

void LoopStats::Tick(Clock::time_point now) {
  if (started_) {
    periods_s_[next_] = std::chrono::duration<double>(now - last_).count();
    next_ = (next_ + 1) % kWindow;
    count_ = std::min(count_ + 1, kWindow);
    // Recompute the summary every 32 ticks: cheap enough for a 1 kHz loop.
    if (next_ % 32 == 0) {
      double sum = 0, worst = 0;
      for (std::size_t i = 0; i < count_; ++i) sum += periods_s_[i], worst = std::max(worst, periods_s_[i]);
      const double mean = sum / static_cast<double>(count_);
      double var = 0;
      for (std::size_t i = 0; i < count_; ++i) var += (periods_s_[i] - mean) * (periods_s_[i] - mean);
      rate_hz_.store(mean > 0 ? 1.0 / mean : 0.0, std::memory_order_relaxed);
      jitter_ms_.store(1e3 * std::sqrt(var / static_cast<double>(count_)), std::memory_order_relaxed);
      worst_ms_.store(1e3 * worst, std::memory_order_relaxed);
    }
  }
  last_ = now;
  started_ = true;
}

LoopRate LoopStats::Snapshot() const {
  return {rate_hz_.load(std::memory_order_relaxed), jitter_ms_.load(std::memory_order_relaxed),
          worst_ms_.load(std::memory_order_relaxed)};
}

}  // namespace vesica::app
