#include "device/bridge_loop.h"

#include <pthread.h>
#include <sched.h>

#include <cstring>

namespace vesica::device {

void BridgeLoop::Start(std::function<void()> after_tick) {
  if (running_.exchange(true)) return;
  thread_ = std::thread([this, after_tick = std::move(after_tick)] {
    if (realtime_priority_ > 0) {
      sched_param param{};
      param.sched_priority = realtime_priority_;
      if (const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param); rc != 0) {
        std::lock_guard lock(error_mu_);
        realtime_error_ = std::string("SCHED_FIFO priority ") + std::to_string(realtime_priority_) + ": " + std::strerror(rc);
      }
    }
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

std::string BridgeLoop::realtime_error() const {
  std::lock_guard lock(error_mu_);
  return realtime_error_;
}

void BridgeLoop::Stop() {
  running_.store(false);
  if (thread_.joinable()) thread_.join();
}

}  // namespace vesica::device
