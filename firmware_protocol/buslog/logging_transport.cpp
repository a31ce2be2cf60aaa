// Forwards to the inner transport; logs what went out and what came in.
#include "firmware_protocol/buslog/logging_transport.h"

#include <algorithm>

#include "firmware_protocol/buslog/candump_format.h"

namespace vesica::fp {

LoggingTransport::LoggingTransport(Transport& inner, BusLogWriter& log, std::string interface)
    : inner_(inner), log_(log), interface_(std::move(interface)) {
  format_candump_line({Nanoseconds{0}, interface_, CanFrame{}});  // checks the name now, not at the first frame
}

SendStatus LoggingTransport::send(const CanFrame& frame, Nanoseconds deadline) {
  const SendStatus s = inner_.send(frame, deadline);
  if (s == SendStatus::Queued) log(inner_.now(), frame);
  return s;
}

bool LoggingTransport::receive(TimedFrame& out) {
  if (!inner_.receive(out)) return false;
  log(out.timestamp, out.frame);
  return true;
}

void LoggingTransport::log(Nanoseconds t, const CanFrame& frame) {
  // A clock before its epoch (never on SocketCAN) is logged as 0 rather than lost.
  log_.write({std::max(t, Nanoseconds{0}), interface_, frame});
}

}  // namespace vesica::fp
