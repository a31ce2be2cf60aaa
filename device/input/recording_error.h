#pragma once

#include <optional>
#include <stdexcept>
#include <string>

namespace vesica::device {

/// A recording that cannot be read. what() is "SOURCE:LINE (t=T s): WHAT", the "(t=T s)" part
/// only when a time is known: the breaking row's time_s when it parsed, else the last good row's.
/// An unreadable file has line 0 and the message names the path.
class RecordingError : public std::runtime_error {
 public:
  RecordingError(const std::string& source_name, int line, std::optional<double> time_s, const std::string& what);

  /// 1-based line where the recording breaks; 0 when the file could not be read at all.
  int line() const { return line_; }
  /// Time (s) of the breaking row, or of the last good row before it; nullopt before any row.
  std::optional<double> time_s() const { return time_s_; }

 private:
  int line_;
  std::optional<double> time_s_;
};

}  // namespace vesica::device
