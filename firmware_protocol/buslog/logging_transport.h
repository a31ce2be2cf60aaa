// A transport that writes every frame it sends and receives to a bus log (bus_log_writer.h), for
// any host session (calibration tool, bridge, trainer) to record its bus traffic as candump would.
// Use:
//   auto can = SocketCanTransport::open(config, err);
//   std::ofstream file("session.log"); BusLogWriter log(file);
//   LoggingTransport bus(*can, log, "can0");        // use `bus` wherever `*can` was used
// A sent frame is logged when the inner transport accepts it (SendStatus::Queued) with the inner
// transport's now() (not its later time on the wire); a received frame with its receive timestamp.
// Not thread-safe, like the transports it wraps. Host side only.
#pragma once

#include <string>

#include "firmware_protocol/buslog/bus_log_writer.h"
#include "firmware_protocol/transport/transport.h"

namespace vesica::fp {

class LoggingTransport final : public Transport {
 public:
  // `inner` and `log` must outlive this; `interface` is the name written on every line (1..15
  // characters, no spaces; std::invalid_argument otherwise).
  LoggingTransport(Transport& inner, BusLogWriter& log, std::string interface);

  SendStatus send(const CanFrame& frame, Nanoseconds deadline) override;
  bool receive(TimedFrame& out) override;
  bool poll_event(BusEvent& out) override { return inner_.poll_event(out); }
  bool wait(Nanoseconds timeout) override { return inner_.wait(timeout); }
  Nanoseconds now() const override { return inner_.now(); }
  BusState state() const override { return inner_.state(); }
  TransportStats stats() const override { return inner_.stats(); }

 private:
  void log(Nanoseconds t, const CanFrame& frame);

  Transport& inner_;
  BusLogWriter& log_;
  std::string interface_;
};

}  // namespace vesica::fp
