// Virtual CAN bus: arbitration by identifier, exact frame times, error frames, injected clock.
#include "firmware_protocol/transport/virtual_bus.h"

#include <limits>

namespace vesica::fp {

namespace {
constexpr int kWarningLimit = 96;   // ISO 11898-1 error counter thresholds
constexpr int kPassiveLimit = 128;
constexpr int kBusOffLimit = 256;
}  // namespace

Nanoseconds VirtualBusEndpoint::now() const { return bus_.clock_.now(); }

SendStatus VirtualBusEndpoint::send(const CanFrame& frame, Nanoseconds deadline) {
  if (!connected_) return SendStatus::Closed;
  if (state_ == BusState::BusOff) return SendStatus::BusOff;
  if (frame.fd() ? !is_valid_fd_length(frame.len) : frame.len > kClassicMaxLength) {
    return SendStatus::Invalid;
  }
  const Nanoseconds t = now();
  if (deadline < t) {
    ++stats_.tx_dropped;
    return SendStatus::DeadlineMissed;
  }
  if (tx_.size() >= bus_.config_.tx_queue_depth) {
    ++stats_.tx_dropped;
    return SendStatus::QueueFull;
  }
  tx_.push_back({frame, t, deadline});
  return SendStatus::Queued;
}

bool VirtualBusEndpoint::receive(TimedFrame& out) {
  if (rx_.empty()) return false;
  out = rx_.front();
  rx_.pop_front();
  return true;
}

bool VirtualBusEndpoint::poll_event(BusEvent& out) {
  if (events_.empty()) return false;
  out = events_.front();
  events_.pop_front();
  return true;
}

void VirtualBusEndpoint::set_connected(bool connected) {
  if (connected_ == connected) return;
  connected_ = connected;
  if (!connected) {
    tx_.clear();
    state_ = BusState::Down;
    push_event(BusEvent::Kind::DeviceLost, 0, now());
  } else {
    tec_ = rec_ = 0;
    state_ = BusState::ErrorActive;
    push_event(BusEvent::Kind::StateChanged, 0, now());
  }
}

void VirtualBusEndpoint::push_event(BusEvent::Kind kind, std::uint32_t detail, Nanoseconds t) {
  events_.push_back({kind, state_, detail, t});
}

void VirtualBusEndpoint::deliver(const CanFrame& f, Nanoseconds t) {
  if (!connected_) return;
  if (rx_.size() >= bus_.config_.rx_queue_depth) {
    ++stats_.rx_dropped;
    push_event(BusEvent::Kind::RxOverflow, 1, t);
    return;
  }
  rx_.push_back({f, t});
  ++stats_.rx_frames;
}

void VirtualBusEndpoint::update_state(Nanoseconds t) {
  BusState s = BusState::ErrorActive;
  if (tec_ >= kBusOffLimit) s = BusState::BusOff;
  else if (tec_ >= kPassiveLimit || rec_ >= kPassiveLimit) s = BusState::ErrorPassive;
  else if (tec_ >= kWarningLimit || rec_ >= kWarningLimit) s = BusState::ErrorWarning;
  if (s == state_) return;
  state_ = s;
  if (s == BusState::BusOff) tx_.clear();  // a bus-off controller drops its queue
  push_event(BusEvent::Kind::StateChanged, static_cast<std::uint32_t>(s), t);
}

VirtualBusEndpoint& VirtualBus::attach(std::string name) {
  endpoints_.push_back(std::unique_ptr<VirtualBusEndpoint>(new VirtualBusEndpoint(*this, std::move(name))));
  return *endpoints_.back();
}

// Starts the next transmission at or after bus_free_at_ if one can start before `limit`.
bool VirtualBus::start_next(Nanoseconds limit) {
  for (;;) {
    // The bus goes idle at bus_free_at_; the first frame waiting then (or arriving later) starts it.
    Nanoseconds start = Nanoseconds::max();
    for (auto& ep : endpoints_)
      if (!ep->tx_.empty()) start = std::min(start, std::max(bus_free_at_, ep->tx_.front().enqueued));
    if (start == Nanoseconds::max() || start > limit) return false;
    // Frames whose deadline passed before they could start are dropped, not sent late.
    bool dropped = false;
    for (auto& ep : endpoints_) {
      while (!ep->tx_.empty() && ep->tx_.front().enqueued <= start && ep->tx_.front().deadline < start) {
        ++ep->stats_.tx_dropped;
        ep->push_event(BusEvent::Kind::TxDropped, ep->tx_.front().frame.id, start);
        ep->tx_.pop_front();
        dropped = true;
      }
    }
    if (dropped) continue;
    // Arbitration: lowest identifier among the heads waiting at `start` (standard before extended
    // with the same base id, as the IDE bit is recessive).
    VirtualBusEndpoint* winner = nullptr;
    std::uint64_t best = std::numeric_limits<std::uint64_t>::max();
    for (auto& ep : endpoints_) {
      if (ep->tx_.empty() || ep->tx_.front().enqueued > start) continue;
      const CanFrame& f = ep->tx_.front().frame;
      const std::uint64_t key = f.extended() ? ((static_cast<std::uint64_t>(f.id >> 18) << 1 | 1) << 18 | (f.id & 0x3FFFF))
                                             : (static_cast<std::uint64_t>(f.id) << 1) << 18;
      if (key < best) { best = key; winner = ep.get(); }
    }
    const CanFrame& f = winner->tx_.front().frame;
    Nanoseconds duration{static_cast<std::int64_t>(frame_duration_ns(f, config_.rates))};
    flight_ = {winner, start, start + duration, false};
    if (errors_to_inject_ > 0) {
      // The error is signalled in the last data bits; model: the whole frame plus an error frame.
      --errors_to_inject_;
      flight_.corrupted = true;
      flight_.end += Nanoseconds{1'000'000'000ll * config_.error_frame_bits / config_.rates.nominal_bps};
    }
    in_flight_ = true;
    return true;
  }
}

void VirtualBus::finish(Nanoseconds t) {
  in_flight_ = false;
  bus_free_at_ = t;
  busy_ += flight_.end - flight_.start;
  VirtualBusEndpoint* sender = flight_.sender;
  // The sender was unplugged while its frame was on the wire (its queue is gone): the frame is
  // cut off, nobody receives it.
  if (sender->tx_.empty()) return;
  if (flight_.corrupted) {
    ++error_frames_;
    sender->tec_ += 8;
    ++sender->stats_.error_frames;
    sender->push_event(BusEvent::Kind::ErrorFrame, 0, t);
    for (auto& ep : endpoints_) {
      if (ep.get() == sender || !ep->connected_) continue;
      ep->rec_ += 1;
      ++ep->stats_.error_frames;
      ep->push_event(BusEvent::Kind::ErrorFrame, 0, t);
      ep->update_state(t);
    }
    sender->update_state(t);  // the frame stays queued and is retried unless now bus-off
    return;
  }
  const CanFrame f = sender->tx_.front().frame;
  sender->tx_.pop_front();
  ++sender->stats_.tx_frames;
  ++frames_;
  if (sender->tec_ > 0) --sender->tec_;
  sender->update_state(t);
  for (auto& ep : endpoints_) {
    if (ep.get() == sender) continue;
    if (ep->rec_ > 0) --ep->rec_;
    ep->update_state(t);
    ep->deliver(f, t);
  }
}

void VirtualBus::run_until(Nanoseconds t) {
  for (;;) {
    if (in_flight_) {
      if (flight_.end > t) break;
      finish(flight_.end);
      continue;
    }
    if (!start_next(t)) break;
  }
  clock_.set(t);
}

double VirtualBus::load() const {
  const Nanoseconds elapsed = clock_.now() - load_reset_time_;
  if (elapsed.count() <= 0) return 0.0;
  return static_cast<double>((busy_ - load_reset_busy_).count()) / static_cast<double>(elapsed.count());
}

void VirtualBus::reset_load() {
  load_reset_time_ = clock_.now();
  load_reset_busy_ = busy_;
}

}  // namespace vesica::fp
