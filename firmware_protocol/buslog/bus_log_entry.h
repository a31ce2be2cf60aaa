// One line of a bus log: when, on which interface, which frame.
// Use: BusLogWriter (bus_log_writer.h) writes these in can-utils' candump log format,
// BusLogReader (bus_log_reader.h) reads them back; candump_format.h converts one line.
// Host side only (std::string).
#pragma once

#include <string>

#include "firmware_protocol/codec/can_frame.h"
#include "firmware_protocol/transport/transport.h"

namespace vesica::fp {

struct BusLogEntry {
  // On the logging transport's clock (SocketCAN: CLOCK_REALTIME, as candump's). The file keeps
  // microseconds, so a written timestamp reads back truncated to a whole microsecond; >= 0.
  Nanoseconds timestamp{0};
  std::string interface;  // 1..15 printable characters, no spaces (a Linux interface name)
  CanFrame frame;
};

}  // namespace vesica::fp
