// Linux SocketCAN raw transport (CAN_RAW) for real arms on can0, or vcan0 in tests.
// Features: receive filters, error frames as bus-state/error events, CAN FD frames, kernel receive
// timestamps (SO_TIMESTAMPNS), receive-overflow counts (SO_RXQ_OVFL), ENOBUFS waits up to the deadline.
// Use:
//   std::string err;
//   auto t = SocketCanTransport::open({.interface = "can0", .fd_frames = true,
//                                      .filters = {{0x180, 0x780}}}, err);
//   if (!t) { /* err names the failing call, e.g. "socket(AF_CAN): Address family not supported" */ }
// Compiles everywhere (Linux headers); on kernels without AF_CAN open() fails with a stated reason.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "firmware_protocol/transport/transport.h"

namespace vesica::fp {

struct CanIdFilter {
  std::uint32_t id = 0;
  std::uint32_t mask = 0;  // received when (frame.id & mask) == (id & mask)
};

struct SocketCanConfig {
  std::string interface = "can0";
  bool fd_frames = false;           // CAN_RAW_FD_FRAMES: send and receive CAN FD frames
  bool receive_own = false;         // CAN_RAW_RECV_OWN_MSGS
  bool loopback = true;             // CAN_RAW_LOOPBACK: other sockets on this host see our frames
  std::vector<CanIdFilter> filters; // empty: everything
  bool error_frames = true;         // subscribe to all error classes
};

class SocketCanTransport final : public Transport {
 public:
  static std::unique_ptr<SocketCanTransport> open(const SocketCanConfig& config, std::string& error);
  // True when this kernel can create a CAN_RAW socket at all (false: EAFNOSUPPORT etc.).
  static bool kernel_supports_can(std::string& why_not);
  ~SocketCanTransport() override;
  SocketCanTransport(const SocketCanTransport&) = delete;
  SocketCanTransport& operator=(const SocketCanTransport&) = delete;

  SendStatus send(const CanFrame& frame, Nanoseconds deadline) override;
  bool receive(TimedFrame& out) override;
  bool poll_event(BusEvent& out) override;
  bool wait(Nanoseconds timeout) override;
  Nanoseconds now() const override;  // CLOCK_REALTIME, the kernel's SO_TIMESTAMPNS clock
  BusState state() const override { return state_; }
  TransportStats stats() const override { return stats_; }

 private:
  SocketCanTransport() = default;
  void drain_socket();
  void handle_error_frame(const std::uint8_t* data, std::uint32_t id, Nanoseconds t);
  void set_state(BusState s, Nanoseconds t);

  int fd_ = -1;
  bool fd_frames_ = false;
  std::uint32_t last_overflow_count_ = 0;
  std::deque<TimedFrame> rx_;
  std::deque<BusEvent> events_;
  TransportStats stats_;
  BusState state_ = BusState::ErrorActive;
};

}  // namespace vesica::fp
