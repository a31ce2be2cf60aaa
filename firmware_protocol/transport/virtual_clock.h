// A clock that moves only when told: the time base of the virtual bus and of deterministic tests.
// Use: VirtualClock clock; clock.advance(1ms); clock.now(). Shared by reference; not thread-safe.
#pragma once

#include <chrono>

namespace vesica::fp {

class VirtualClock {
 public:
  std::chrono::nanoseconds now() const { return now_; }
  void advance(std::chrono::nanoseconds dt) { now_ += dt; }
  void set(std::chrono::nanoseconds t) { if (t > now_) now_ = t; }  // never backwards

 private:
  std::chrono::nanoseconds now_{0};
};

}  // namespace vesica::fp
