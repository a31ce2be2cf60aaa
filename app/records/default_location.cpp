#include "app/records/default_location.h"

#include <pwd.h>
#include <unistd.h>

#include <cstdlib>

#include "app/records/session_store.h"

namespace vesica::app {
namespace {

bool NonEmpty(const char* value) { return value != nullptr && value[0] != '\0'; }

}  // namespace

std::filesystem::path DefaultSessionDatabasePath(const EnvLookup& getenv) {
  const char* xdg = getenv("XDG_DATA_HOME");
  if (NonEmpty(xdg) && std::filesystem::path(xdg).is_absolute()) {
    return std::filesystem::path(xdg) / "vesica" / "sessions.sqlite";
  }
  std::filesystem::path home;
  if (const char* env_home = getenv("HOME"); NonEmpty(env_home)) {
    home = env_home;
  } else if (const passwd* user = getpwuid(getuid()); user != nullptr && NonEmpty(user->pw_dir)) {
    home = user->pw_dir;
  } else {
    throw RecordsError(
        "session database: no default location: XDG_DATA_HOME and HOME are unset and "
        "the user has no home directory; pass --db");
  }
  return home / ".local" / "share" / "vesica" / "sessions.sqlite";
}

std::string DefaultSessionStoreLocation(const EnvLookup& getenv) {
  if (const char* location = getenv("VESICA_RECORDS_DB"); NonEmpty(location)) return location;
  return DefaultSessionDatabasePath(getenv).string();
}

std::string DefaultSessionStoreLocation() {
  return DefaultSessionStoreLocation([](const char* name) { return std::getenv(name); });
}

}  // namespace vesica::app
