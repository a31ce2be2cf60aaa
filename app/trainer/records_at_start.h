#pragma once
// The records location is checked when the trainer starts, not when the first session ends: a
// location that cannot hold a database (XDG_DATA_HOME a file, a folder that cannot be created,
// a file that is not a database) is a clear error at start instead of a lost session later.

#include <string>

namespace vesica::app {

/// Opens (creating if needed) the SQLite store at `location`; throws std::runtime_error saying
/// what is wrong and where the location came from. A PostgreSQL location is not required to be
/// up: sessions wait in the pending file until it is (returns a warning text then, else "").
std::string CheckRecordsLocationAtStart(const std::string& location);

}  // namespace vesica::app
