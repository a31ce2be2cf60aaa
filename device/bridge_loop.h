#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "device/can_arm.h"

namespace vesica::device {

/// Runs CanArm::Tick() at a fixed period on its own thread (the 1 kHz device loop), against the
/// steady clock. Ticks are scheduled on an absolute grid; a late tick is not made up for by a
/// burst, the grid restarts from now. Tests on the virtual bus call Tick() themselves instead.
class BridgeLoop {
 public:
  explicit BridgeLoop(CanArm& arm, std::chrono::nanoseconds period = std::chrono::milliseconds(1))
      : arm_(arm), period_(period) {}
  ~BridgeLoop() { Stop(); }
  BridgeLoop(const BridgeLoop&) = delete;
  BridgeLoop& operator=(const BridgeLoop&) = delete;

  /// after_tick (optional) runs on the loop thread after every tick, e.g. to set the next force.
  void Start(std::function<void()> after_tick = {});
  /// Ask for SCHED_FIFO at this priority (1..99) for the loop thread before Start(); 0 = normal
  /// scheduling. Refusal (no CAP_SYS_NICE) leaves the loop running normally; see realtime_error().
  void set_realtime_priority(int priority) { realtime_priority_ = priority; }
  /// Empty if the requested real-time scheduling took effect (or none was asked for).
  std::string realtime_error() const;
  void Stop();
  bool running() const { return running_.load(); }
  std::uint64_t ticks() const { return ticks_.load(); }
  std::uint64_t overruns() const { return overruns_.load(); }  ///< ticks that started a period late

 private:
  CanArm& arm_;
  std::chrono::nanoseconds period_;
  std::atomic<bool> running_{false};
  std::atomic<std::uint64_t> ticks_{0};
  std::atomic<std::uint64_t> overruns_{0};
  std::thread thread_;
  int realtime_priority_ = 0;
  mutable std::mutex error_mu_;
  std::string realtime_error_;
};

}  // namespace vesica::device
