#pragma once
// Where a station keeps its sessions when nobody says otherwise.

#include <filesystem>
#include <functional>
#include <string>

namespace vesica::app {

/// Reads one environment variable; nullptr when unset (std::getenv's contract). Tests pass a map.
using EnvLookup = std::function<const char*(const char*)>;

/// $XDG_DATA_HOME/vesica/sessions.sqlite, or ~/.local/share/vesica/sessions.sqlite when
/// XDG_DATA_HOME is unset, empty or relative (the XDG base directory rule); ~ is $HOME, or the
/// password database's home directory when HOME is unset or empty. Throws RecordsError when no
/// home directory can be found.
std::filesystem::path DefaultSessionDatabasePath(const EnvLookup& getenv);

/// $VESICA_RECORDS_DB when set and non-empty (a file path or a PostgreSQL connection string:
/// this is how a station is pointed at a shared server), else DefaultSessionDatabasePath.
std::string DefaultSessionStoreLocation(const EnvLookup& getenv);

/// DefaultSessionStoreLocation of this process's environment (std::getenv).
std::string DefaultSessionStoreLocation();

}  // namespace vesica::app
