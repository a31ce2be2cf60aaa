#pragma once
// Rate and period jitter of a loop over its last N ticks (the diagnostics overlay shows them).
// Written by the loop's own thread; read from others through Snapshot() (atomic copies).

#include <array>
#include <atomic>
#include <chrono>
#include <cstddef>

namespace vesica::app {

struct LoopRate {
  double rate_hz = 0;    ///< ticks per second over the window
  double jitter_ms = 0;  ///< standard deviation of the period
  double worst_ms = 0;   ///< longest period in the window
};

class LoopStats {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr std::size_t kWindow = 256;

  /// Called once per iteration by the loop's thread.
  void Tick(Clock::time_point now);
  /// Safe from any thread.
  LoopRate Snapshot() const;

 private:
  std::array<double, kWindow> periods_s_{};
  std::size_t count_ = 0, next_ = 0;
  Clock::time_point last_{};
  bool started_ = false;
  std::atomic<double> rate_hz_{0}, jitter_ms_{0}, worst_ms_{0};
};

}  // namespace vesica::app
