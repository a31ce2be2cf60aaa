// In-process CAN bus, bit-accurate in time, driven by an injected VirtualClock.
// Each frame occupies the bus for its exact stuffed length (frame_timing.h); when the bus goes idle
// the lowest identifier among the waiting frames wins arbitration; receivers get the frame at its
// end-of-frame time. Error injection destroys frames with an error frame (the sender retransmits,
// ISO 11898-1 error counters move the sender through warning/passive/bus-off).
// Use:
//   VirtualClock clock; VirtualBus bus(clock);
//   Transport& host = bus.attach("host"); Transport& arm = bus.attach("arm1");
//   host.send(frame, clock.now() + 1ms);  bus.advance(200us);  arm.receive(rx);
//   bus.load() -> busy fraction since the last reset_load().
// Single-threaded by design (determinism); not thread-safe.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "firmware_protocol/codec/frame_timing.h"
#include "firmware_protocol/transport/transport.h"
#include "firmware_protocol/transport/virtual_clock.h"

namespace vesica::fp {

class VirtualBus;

class VirtualBusEndpoint final : public Transport {
 public:
  SendStatus send(const CanFrame& frame, Nanoseconds deadline) override;
  bool receive(TimedFrame& out) override;
  bool poll_event(BusEvent& out) override;
  bool wait(Nanoseconds) override { return !rx_.empty() || !events_.empty(); }
  Nanoseconds now() const override;
  BusState state() const override { return state_; }
  TransportStats stats() const override { return stats_; }

  const std::string& name() const { return name_; }
  // Unplug (false) or replug (true): unplugged endpoints neither send nor receive (DeviceLost event).
  void set_connected(bool connected);
  bool connected() const { return connected_; }
  std::size_t pending_tx() const { return tx_.size(); }
  int transmit_error_counter() const { return tec_; }
  int receive_error_counter() const { return rec_; }

 private:
  friend class VirtualBus;
  struct Pending {
    CanFrame frame;
    Nanoseconds enqueued;
    Nanoseconds deadline;
  };
  VirtualBusEndpoint(VirtualBus& bus, std::string name) : bus_(bus), name_(std::move(name)) {}
  void push_event(BusEvent::Kind kind, std::uint32_t detail, Nanoseconds t);
  void deliver(const CanFrame& f, Nanoseconds t);
  void update_state(Nanoseconds t);

  VirtualBus& bus_;
  std::string name_;
  std::deque<Pending> tx_;
  std::deque<TimedFrame> rx_;
  std::deque<BusEvent> events_;
  TransportStats stats_;
  BusState state_ = BusState::ErrorActive;
  bool connected_ = true;
  int tec_ = 0;  // transmit error counter
  int rec_ = 0;  // receive error counter
};

class VirtualBus {
 public:
  struct Config {
    BitRates rates{};
    std::size_t tx_queue_depth = 64;    // per endpoint, like a socket's send queue
    std::size_t rx_queue_depth = 4096;  // per endpoint
    std::uint32_t error_frame_bits = 6 + 8 + 3;  // error flag + delimiter + intermission
  };

  explicit VirtualBus(VirtualClock& clock) : VirtualBus(clock, Config{}) {}
  VirtualBus(VirtualClock& clock, Config config) : clock_(clock), config_(config) {}

  // A new station on the bus, owned by the bus.
  VirtualBusEndpoint& attach(std::string name);

  // Simulates the bus up to time t (arbitration, transmissions, deliveries) and sets the clock to t.
  void run_until(Nanoseconds t);
  void advance(Nanoseconds dt) { run_until(clock_.now() + dt); }

  // The next n transmissions are destroyed by an error frame and retried by their sender.
  void inject_errors(int n) { errors_to_inject_ += n; }

  // Busy fraction of bus time (frames, error frames, interframe space) since reset_load().
  double load() const;
  void reset_load();
  Nanoseconds busy_time() const { return busy_; }
  std::uint64_t frames_transmitted() const { return frames_; }
  std::uint64_t error_frames() const { return error_frames_; }

  VirtualClock& clock() { return clock_; }
  const Config& config() const { return config_; }

 private:
  friend class VirtualBusEndpoint;
  struct InFlight {
    VirtualBusEndpoint* sender = nullptr;
    Nanoseconds start{0};
    Nanoseconds end{0};
    bool corrupted = false;
  };
  bool start_next(Nanoseconds limit);
  void finish(Nanoseconds t);

  VirtualClock& clock_;
  Config config_;
  std::vector<std::unique_ptr<VirtualBusEndpoint>> endpoints_;
  bool in_flight_ = false;
  InFlight flight_;
  Nanoseconds bus_free_at_{0};
  Nanoseconds busy_{0};
  Nanoseconds load_reset_time_{0};
  Nanoseconds load_reset_busy_{0};
  std::uint64_t frames_ = 0;
  std::uint64_t error_frames_ = 0;
  int errors_to_inject_ = 0;
};

}  // namespace vesica::fp
