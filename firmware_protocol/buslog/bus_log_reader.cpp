// Line by line over candump_format.h's parser, keeping the line number for error messages.
#include "firmware_protocol/buslog/bus_log_reader.h"

#include "firmware_protocol/buslog/candump_format.h"

namespace vesica::fp {

bool BusLogReader::next(BusLogEntry& out) {
  if (!error_.empty()) return false;
  std::string line, why;
  while (std::getline(in_, line)) {
    ++line_;
    switch (parse_candump_line(line, out, why)) {
      case CandumpLine::Frame: return true;
      case CandumpLine::Ignored: break;
      case CandumpLine::ErrorFrame: ++error_frames_; break;
      case CandumpLine::Malformed:
        error_ = "line " + std::to_string(line_) + ", " + why;
        return false;
    }
  }
  return false;
}

bool read_bus_log(std::istream& in, std::vector<BusLogEntry>& out, std::string& error) {
  BusLogReader reader(in);
  BusLogEntry e;
  while (reader.next(e)) out.push_back(e);
  error = reader.error();
  return error.empty();
}

}  // namespace vesica::fp
