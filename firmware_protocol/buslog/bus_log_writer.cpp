// One candump line per frame.
#include "firmware_protocol/buslog/bus_log_writer.h"

#include "firmware_protocol/buslog/candump_format.h"

namespace vesica::fp {

void BusLogWriter::write(const BusLogEntry& entry) {
  const std::string line = format_candump_line(entry);  // throws before anything is written
  out_ << line << '\n';
  ++lines_;
}

}  // namespace vesica::fp
