#include "app/records/session_record.h"

#include <ctime>

namespace vesica::app {

std::string FormatUtcIso8601(std::int64_t unix_s) {
  const std::time_t t = static_cast<std::time_t>(unix_s);
  std::tm utc{};
  if (gmtime_r(&t, &utc) == nullptr) return std::to_string(unix_s);  // out of tm's range
  char text[32];
  const std::size_t n = std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return n > 0 ? std::string(text, n) : std::to_string(unix_s);
}

}  // namespace vesica::app
