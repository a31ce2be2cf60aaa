#pragma once

#include <atomic>
#include <chrono>
#include <functional>
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
};

}  // namespace vesica::device
