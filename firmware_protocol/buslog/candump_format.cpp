// candump log lines: formatting as can-utils' lib.c sprint_canframe does, parsing as its
// parse_canframe does (stricter where it guesses: ids must be 3 or 8 digits, micros 6 digits).
#include "firmware_protocol/buslog/candump_format.h"

#include <cstdint>
#include <cstdio>
#include <stdexcept>

namespace vesica::fp {
namespace {

constexpr char kHex[] = "0123456789ABCDEF";
constexpr std::uint32_t kSffMask = 0x7FF;
constexpr std::uint32_t kEffMask = 0x1FFFFFFF;
constexpr std::uint32_t kErrFlag = 0x20000000;  // SocketCAN CAN_ERR_FLAG
constexpr std::uint8_t kFdBrs = 0x01;           // SocketCAN CANFD_BRS
constexpr std::uint8_t kFdEsi = 0x02;           // SocketCAN CANFD_ESI
constexpr std::uint8_t kFdFdf = 0x04;           // SocketCAN CANFD_FDF: Linux >= 6.0 sets it on every FD frame
constexpr std::size_t kMaxInterfaceLength = 15; // IFNAMSIZ - 1
constexpr long long kMaxSeconds = 9000000000LL;  // nanoseconds since 1970 must fit an int64

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

void append_hex(std::string& s, std::uint32_t v, int digits) {
  for (int i = digits - 1; i >= 0; --i) s += kHex[(v >> (4 * i)) & 0xF];
}

bool valid_interface(std::string_view name) {
  if (name.empty() || name.size() > kMaxInterfaceLength) return false;
  for (char c : name)
    if (c <= ' ' || c > '~') return false;
  return true;
}

CandumpLine malformed(std::string& error, std::string why) {
  error = std::move(why);
  return CandumpLine::Malformed;
}

// The FRAME part; `text` has no surrounding spaces.
CandumpLine parse_frame(std::string_view text, CanFrame& f, std::string& error) {
  const std::size_t hash = text.find('#');
  if (hash == std::string_view::npos) return malformed(error, "frame '" + std::string(text) + "' has no '#'");
  const std::string_view id_text = text.substr(0, hash);
  if (id_text.size() != 3 && id_text.size() != 8)
    return malformed(error, "CAN id '" + std::string(id_text) + "' is not 3 (11-bit) or 8 (29-bit) hex digits");
  std::uint32_t id = 0;
  for (char c : id_text) {
    const int v = hex_value(c);
    if (v < 0) return malformed(error, "CAN id '" + std::string(id_text) + "' is not hexadecimal");
    id = id << 4 | static_cast<std::uint32_t>(v);
  }
  f = CanFrame{};
  if (id_text.size() == 8) {
    if (id & kErrFlag) return CandumpLine::ErrorFrame;
    if (id > kEffMask) return malformed(error, "29-bit CAN id " + std::string(id_text) + " has flag bits set");
    f.flags |= CanFrame::kExtendedId;
  } else if (id > kSffMask) {
    return malformed(error, "11-bit CAN id " + std::string(id_text) + " is above 7FF");
  }
  f.id = id;

  std::string_view rest = text.substr(hash + 1);
  std::uint8_t max_len = kClassicMaxLength;
  if (!rest.empty() && rest[0] == '#') {
    if (rest.size() < 2 || hex_value(rest[1]) < 0) return malformed(error, "CAN FD frame without its flags digit");
    const int fd_flags = hex_value(rest[1]);
    if (fd_flags & ~(kFdBrs | kFdEsi | kFdFdf)) return malformed(error, "CAN FD flags " + std::string(1, rest[1]) + " unknown");
    f.flags |= CanFrame::kFdFrame;
    if (fd_flags & kFdBrs) f.flags |= CanFrame::kBitRateSwitch;
    max_len = kFdMaxLength;
    rest = rest.substr(2);
  } else if (!rest.empty() && (rest[0] == 'R' || rest[0] == 'r')) {
    f.flags |= CanFrame::kRemote;
    if (rest.size() == 1) return CandumpLine::Frame;
    const int len = rest.size() == 2 ? hex_value(rest[1]) : -1;
    if (len < 0 || len > kClassicMaxLength) return malformed(error, "remote frame length '" + std::string(rest.substr(1)) + "' is not 0..8");
    f.len = static_cast<std::uint8_t>(len);
    return CandumpLine::Frame;
  }
  std::size_t i = 0;
  while (i < rest.size()) {
    if (rest[i] == '.') { ++i; continue; }  // canplayer accepts '.' between bytes
    if (i + 1 >= rest.size() || hex_value(rest[i]) < 0 || hex_value(rest[i + 1]) < 0)
      return malformed(error, "data '" + std::string(rest) + "' is not hex byte pairs");
    if (f.len == max_len)
      return malformed(error, "data longer than " + std::to_string(max_len) + " bytes");
    f.data[f.len++] = static_cast<std::uint8_t>(hex_value(rest[i]) << 4 | hex_value(rest[i + 1]));
    i += 2;
  }
  if (f.fd() && !is_valid_fd_length(f.len))
    return malformed(error, "CAN FD length " + std::to_string(f.len) + " is not a DLC step (0..8, 12, 16, 20, 24, 32, 48, 64)");
  return CandumpLine::Frame;
}

}  // namespace

std::string format_candump_frame(const CanFrame& f) {
  if (f.extended() ? f.id > kEffMask : f.id > kSffMask)
    throw std::invalid_argument("CAN id " + std::to_string(f.id) + " too wide for its format");
  if (f.fd() ? !is_valid_fd_length(f.len) : f.len > kClassicMaxLength)
    throw std::invalid_argument("frame length " + std::to_string(f.len) + " invalid");
  if (f.fd() && f.remote()) throw std::invalid_argument("CAN FD has no remote frames");
  if (!f.fd() && f.brs()) throw std::invalid_argument("bit-rate switch on a classic frame");
  std::string s;
  append_hex(s, f.id, f.extended() ? 8 : 3);
  s += '#';
  if (f.remote()) {
    s += 'R';
    if (f.len > 0) s += kHex[f.len];  // candump writes the requested length only when non-zero
    return s;
  }
  if (f.fd()) {
    s += '#';
    s += kHex[kFdFdf | (f.brs() ? kFdBrs : 0)];  // as candump writes on Linux >= 6.0
  }
  for (std::uint8_t i = 0; i < f.len; ++i) append_hex(s, f.data[i], 2);
  return s;
}

std::string format_candump_line(const BusLogEntry& e) {
  if (e.timestamp.count() < 0) throw std::invalid_argument("negative timestamp");
  if (!valid_interface(e.interface))
    throw std::invalid_argument("interface name '" + e.interface + "' is not 1..15 characters without spaces");
  const long long us = e.timestamp.count() / 1000;
  char stamp[48];
  std::snprintf(stamp, sizeof stamp, "(%010lld.%06lld) ", us / 1000000, us % 1000000);
  return stamp + e.interface + ' ' + format_candump_frame(e.frame);
}

CandumpLine parse_candump_line(std::string_view line, BusLogEntry& out, std::string& error) {
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t')) line.remove_suffix(1);
  if (line.empty() || line[0] != '(') return CandumpLine::Ignored;
  const std::size_t close = line.find(')');
  if (close == std::string_view::npos) return malformed(error, "column 1: timestamp has no ')'");
  const std::string_view stamp = line.substr(1, close - 1);
  const std::size_t dot = stamp.find('.');
  if (dot == std::string_view::npos || dot == 0 || stamp.size() - dot - 1 != 6)
    return malformed(error, "column 2: timestamp '" + std::string(stamp) + "' is not seconds.micros (6 digits)");
  long long seconds = 0, micros = 0;
  for (std::size_t i = 0; i < stamp.size(); ++i) {
    if (i == dot) continue;
    if (stamp[i] < '0' || stamp[i] > '9' || dot > 12)
      return malformed(error, "column 2: timestamp '" + std::string(stamp) + "' is not seconds.micros");
    long long& v = i < dot ? seconds : micros;
    v = v * 10 + (stamp[i] - '0');
  }
  if (seconds > kMaxSeconds) return malformed(error, "column 2: timestamp '" + std::string(stamp) + "' is beyond the year 2255");

  // Then one or more spaces, the interface (candump right-aligns names), spaces, the frame.
  std::size_t p = close + 1;
  auto skip_spaces = [&] { const std::size_t s = p; while (p < line.size() && line[p] == ' ') ++p; return p > s; };
  auto word = [&] { const std::size_t s = p; while (p < line.size() && line[p] != ' ') ++p; return line.substr(s, p - s); };
  if (!skip_spaces()) return malformed(error, "column " + std::to_string(p + 1) + ": no space after the timestamp");
  const std::size_t iface_col = p + 1;
  const std::string_view iface = word();
  if (!valid_interface(iface)) return malformed(error, "column " + std::to_string(iface_col) + ": interface name '" + std::string(iface) + "' invalid");
  if (!skip_spaces()) return malformed(error, "column " + std::to_string(p + 1) + ": no frame after the interface");
  const std::size_t frame_col = p + 1;
  const std::string_view frame_text = word();
  if (p != line.size()) return malformed(error, "column " + std::to_string(p + 1) + ": text after the frame");

  BusLogEntry e;
  e.timestamp = Nanoseconds{(seconds * 1000000 + micros) * 1000};
  e.interface = std::string(iface);
  std::string why;
  const CandumpLine kind = parse_frame(frame_text, e.frame, why);
  if (kind == CandumpLine::Malformed) return malformed(error, "column " + std::to_string(frame_col) + ": " + why);
  if (kind == CandumpLine::Frame) out = std::move(e);
  return kind;
}

}  // namespace vesica::fp
