#pragma once

#include <cstdint>

namespace vesica::device {

/// Decides from state-frame arrival times whether the link to a node is up. Lost when no state
/// arrived for longer than the timeout; up again at the first state after that. Counts both
/// transitions so a UI can report "link lost 3 times".
class LinkMonitor {
 public:
  /// timeout_ns > 0: how long without a state before the link counts as lost.
  explicit LinkMonitor(std::int64_t timeout_ns) : timeout_ns_(timeout_ns) {}

  enum class Event { kNone, kLost, kRestored };

  /// A valid state frame arrived at now_ns.
  Event OnState(std::int64_t now_ns);
  /// Called every servo cycle; reports kLost once when the timeout passes.
  Event Poll(std::int64_t now_ns);

  bool up() const { return up_; }
  bool ever_seen() const { return ever_seen_; }
  std::uint32_t loss_count() const { return loss_count_; }
  std::uint32_t restore_count() const { return restore_count_; }
  std::int64_t last_state_ns() const { return last_state_ns_; }
  std::int64_t timeout_ns() const { return timeout_ns_; }

 private:
  std::int64_t timeout_ns_;
  std::int64_t last_state_ns_ = 0;
  bool up_ = false;
  bool ever_seen_ = false;
  std::uint32_t loss_count_ = 0;
  std::uint32_t restore_count_ = 0;
};

}  // namespace vesica::device
