#include "device/input/recording_error.h"

#include <array>
#include <charconv>

namespace vesica::device {
namespace {

std::string Message(const std::string& source_name, int line, std::optional<double> time_s, const std::string& what) {
  // Appends piece by piece (GCC 12 warns falsely on "literal" + std::string here).
  std::string out = source_name;
  if (line > 0) out.append(":").append(std::to_string(line));
  if (time_s) {
    std::array<char, 32> buf{};
    const auto end = std::to_chars(buf.data(), buf.data() + buf.size(), *time_s).ptr;
    out.append(" (t=").append(buf.data(), end).append(" s)");
  }
  return out.append(": ").append(what);
}

}  // namespace

RecordingError::RecordingError(const std::string& source_name, int line, std::optional<double> time_s,
                               const std::string& what)
    : std::runtime_error(Message(source_name, line, time_s, what)), line_(line), time_s_(time_s) {}

}  // namespace vesica::device
