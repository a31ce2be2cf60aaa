#include "app/trainer/records_at_start.h"

#include <cstdlib>
#include <stdexcept>

#include "app/records/session_store.h"

namespace vesica::app {

std::string CheckRecordsLocationAtStart(const std::string& location) {
  try {
    OpenSessionStore(location);
    return "";
  } catch (const std::exception& e) {
    if (IsConnectionString(location)) {
      return std::string(e.what()) + "; sessions will wait in the pending file until the server is reachable";
    }
    std::string origin = " (give another with --records FILE, or --records none)";
    const char* records_db = std::getenv("VESICA_RECORDS_DB");
    const char* xdg = std::getenv("XDG_DATA_HOME");
    if (records_db != nullptr && *records_db != '\0' && location == records_db) {
      origin = " (from VESICA_RECORDS_DB; change it, or pass --records FILE or --records none)";
    } else if (xdg != nullptr && *xdg != '\0' && location.starts_with(xdg)) {
      origin = std::string(" (from XDG_DATA_HOME=") + xdg +
               ", which must be a folder; change it, or pass --records FILE or --records none)";
    }
    throw std::runtime_error("the records database cannot be used: " + std::string(e.what()) + origin);
  }
}

}  // namespace vesica::app
