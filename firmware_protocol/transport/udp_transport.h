// CAN over UDP in cannelloni's packet format: lets the arm emulator run as its own process (and a
// real cannelloni gateway join). One frame per datagram, sent at once (latency over batching).
// Use:
//   auto t = UdpTransport::open({.local_port = 20000, .remote_port = 20001});   // 127.0.0.1 default
//   if (!t) log(t.error_text());  then use it as a Transport.
// Lost datagrams show up as RxOverflow events (sequence-number gaps); malformed packets are counted
// in stats().malformed and dropped. Only datagrams from the configured remote address and port are
// accepted; others are counted in stats().foreign and dropped.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <string>

#include "firmware_protocol/transport/transport.h"

namespace vesica::fp {

struct UdpTransportConfig {
  std::string local_address = "127.0.0.1";
  std::uint16_t local_port = 0;  // 0: any free port (see UdpTransport::local_port())
  std::string remote_address = "127.0.0.1";
  std::uint16_t remote_port = 0;
};

class UdpTransport final : public Transport {
 public:
  // Opens and binds the socket; on failure returns nullptr and sets `error` (errno text named).
  static std::unique_ptr<UdpTransport> open(const UdpTransportConfig& config, std::string& error);
  ~UdpTransport() override;
  UdpTransport(const UdpTransport&) = delete;
  UdpTransport& operator=(const UdpTransport&) = delete;

  SendStatus send(const CanFrame& frame, Nanoseconds deadline) override;
  bool receive(TimedFrame& out) override;
  bool poll_event(BusEvent& out) override;
  bool wait(Nanoseconds timeout) override;
  Nanoseconds now() const override;
  BusState state() const override { return state_; }
  TransportStats stats() const override { return stats_; }

  std::uint16_t local_port() const { return local_port_; }
  void set_remote_port(std::uint16_t port);

 private:
  UdpTransport() = default;
  void drain_socket();

  int fd_ = -1;
  std::uint16_t local_port_ = 0;
  unsigned char remote_[16] = {};  // sockaddr_in
  std::uint8_t tx_seq_ = 0;
  bool rx_seq_primed_ = false;
  std::uint8_t rx_seq_ = 0;
  std::deque<TimedFrame> rx_;
  std::deque<BusEvent> events_;
  TransportStats stats_;
  BusState state_ = BusState::ErrorActive;
};

}  // namespace vesica::fp
