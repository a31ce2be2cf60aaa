// Reads a bus log in can-utils' candump log format (ours, or candump -l / -L output), for replay
// and restore tools and for tests that compare logs.
// Use:
//   std::ifstream file("session.log"); BusLogReader log(file); BusLogEntry e;
//   while (log.next(e)) replay(e);
//   if (!log.error().empty()) fail(log.error());   // "line 12, column 29: CAN id ... invalid"
// Comments and blank lines are skipped; SocketCAN error frames are skipped and counted.
// Host side only.
#pragma once

#include <cstdint>
#include <istream>
#include <string>
#include <vector>

#include "firmware_protocol/buslog/bus_log_entry.h"

namespace vesica::fp {

class BusLogReader {
 public:
  explicit BusLogReader(std::istream& in) : in_(in) {}

  // The next frame; false at the end of the input or at a malformed line (error() says which).
  bool next(BusLogEntry& out);

  const std::string& error() const { return error_; }  // empty unless a line was malformed
  std::uint64_t line_number() const { return line_; }   // of the line last read, from 1
  std::uint64_t error_frames_skipped() const { return error_frames_; }

 private:
  std::istream& in_;
  std::string error_;
  std::uint64_t line_ = 0;
  std::uint64_t error_frames_ = 0;
};

// Every frame of a log; false (with `error` set and `out` holding the frames before it) at the
// first malformed line.
bool read_bus_log(std::istream& in, std::vector<BusLogEntry>& out, std::string& error);

}  // namespace vesica::fp
