#include "device/link_monitor.h"

namespace vesica::device {

LinkMonitor::Event LinkMonitor::OnState(std::int64_t now_ns) {
  last_state_ns_ = now_ns;
  const bool was_lost = ever_seen_ && !up_;
  ever_seen_ = true;
  if (up_) return Event::kNone;
  up_ = true;
  if (was_lost) {
    ++restore_count_;
    return Event::kRestored;
  }
  return Event::kNone;  // first contact is not a restoration
}

LinkMonitor::Event LinkMonitor::Poll(std::int64_t now_ns) {
  if (!up_ || now_ns - last_state_ns_ <= timeout_ns_) return Event::kNone;
  up_ = false;
  ++loss_count_;
  return Event::kLost;
}

}  // namespace vesica::device
