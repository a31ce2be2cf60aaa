#include "device/bridge_loop.h"

namespace vesica::device {

void BridgeLoop::Start(std::function<void()> after_tick) {
  if (running_.exchange(true)) return;
  thread_ = std::thread([this, after_tick = std::move(after_tick)] {
    using Clock = std::chrono::steady_clock;
    auto next = Clock::now();
    while (running_.load(std::memory_order_relaxed)) {
      arm_.Tick();
      if (after_tick) after_tick();
      ticks_.fetch_add(1, std::memory_order_relaxed);
      next += period_;
      const auto now = Clock::now();
      if (now > next + period_) {
        overruns_.fetch_add(1, std::memory_order_relaxed);
        next = now;
      }
      std::this_thread::sleep_until(next);
    }
  });
}

void BridgeLoop::Stop() {
  running_.store(false);
  if (thread_.joinable()) thread_.join();
}

}  // namespace vesica::device
