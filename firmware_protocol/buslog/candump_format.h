// can-utils' candump log format, one line at a time: `(seconds.micros) IFACE FRAME` where FRAME is
//   123#DEADBEEF          classic frame, 11-bit id (3 hex digits), data in hex pairs
//   1ABCDEF0#11           29-bit id (8 hex digits)
//   123#R                 remote request (123#R3: with a requested length)
//   123##5AABBCC          CAN FD: one hex digit of flags (1 = bit-rate switch, 2 = ESI, 4 = FD
//                         frame; Linux >= 6.0 sets 4 on every FD frame and candump writes it), then data
// exactly as `candump -l` / `candump -L` write it (upper-case hex, no separators), so canplayer,
// log2asc and candump's own logs interchange with ours. Parsing also takes what canplayer takes:
// lower case and '.' between data bytes. Lines not starting with '(' are comments (canplayer's rule).
// Host side only.
#pragma once

#include <string>
#include <string_view>

#include "firmware_protocol/buslog/bus_log_entry.h"

namespace vesica::fp {

// The FRAME part. Throws std::invalid_argument for a frame no candump line can carry (classic
// length > 8, a CAN FD length that is not a DLC step, an id too wide, an FD remote frame).
std::string format_candump_frame(const CanFrame& frame);

// The whole line, without the newline. Throws std::invalid_argument also for a negative
// timestamp or an interface name that is empty, longer than 15 characters or has spaces.
std::string format_candump_line(const BusLogEntry& entry);

enum class CandumpLine {
  Frame,       // `out` holds the frame
  Ignored,     // comment or blank line
  ErrorFrame,  // a SocketCAN error frame (id flag 0x20000000): valid in a log, not a CanFrame
  Malformed,   // `error` says what is wrong, naming the column
};

// Parses one line (a trailing '\r' or spaces are allowed). The ESI flag of a CAN FD frame is not
// kept: CanFrame has no place for it, and only a node in error-passive sets it.
CandumpLine parse_candump_line(std::string_view line, BusLogEntry& out, std::string& error);

}  // namespace vesica::fp
