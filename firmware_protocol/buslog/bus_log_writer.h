// Writes a bus log in can-utils' candump log format (candump_format.h), one line per frame, so that
// canplayer replays it, log2asc converts it and candump's own logs compare with it line by line.
// Use:
//   std::ofstream file("session.log"); BusLogWriter log(file);
//   log.write({rx.timestamp, "can0", rx.frame});   // or wrap a transport: logging_transport.h
//   log.flush();                                   // before a crash can lose the stream's buffer
// Not thread-safe: one writer per stream, used from one thread. Host side only.
#pragma once

#include <cstdint>
#include <ostream>

#include "firmware_protocol/buslog/bus_log_entry.h"

namespace vesica::fp {

class BusLogWriter {
 public:
  explicit BusLogWriter(std::ostream& out) : out_(out) {}

  // Throws std::invalid_argument (and writes nothing) for an entry no log line can carry.
  void write(const BusLogEntry& entry);
  void flush() { out_.flush(); }

  std::uint64_t lines_written() const { return lines_; }
  bool ok() const { return out_.good(); }  // false once the stream failed (disk full, closed)

 private:
  std::ostream& out_;
  std::uint64_t lines_ = 0;
};

}  // namespace vesica::fp
