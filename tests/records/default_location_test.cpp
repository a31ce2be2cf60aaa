// Where sessions go when nobody says: the XDG data folder of the user, or VESICA_RECORDS_DB.

#include "app/records/default_location.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <pwd.h>
#include <unistd.h>

#include <cstdlib>
#include <map>

#include "app/records/session_store.h"
#include "app/records/sqlite_session_store.h"
#include "tests/records/sample_records.h"
#include "tests/records/scoped_env.h"
#include "tests/records/temp_dir.h"

namespace vesica::app {
namespace {

using testing::SampleRecord;
using testing::ScopedEnv;
using testing::TempDir;

// An EnvLookup over a fixed map: variables not in it are unset.
EnvLookup Env(std::map<std::string, std::string> values) {
  return [values = std::move(values)](const char* name) -> const char* {
    const auto it = values.find(name);
    return it != values.end() ? it->second.c_str() : nullptr;
  };
}

const char* RealEnv(const char* name) { return std::getenv(name); }

TEST(DefaultLocationTest, XdgDataHomeWhenAbsolute) {
  EXPECT_EQ(DefaultSessionDatabasePath(Env({{"XDG_DATA_HOME", "/data/ana"}, {"HOME", "/home/ana"}})),
            "/data/ana/vesica/sessions.sqlite");
}

TEST(DefaultLocationTest, HomeLocalShareWhenXdgDataHomeUnsetEmptyOrRelative) {
  for (const auto& env : {Env({{"HOME", "/home/ana"}}), Env({{"XDG_DATA_HOME", ""}, {"HOME", "/home/ana"}}),
                          Env({{"XDG_DATA_HOME", "data"}, {"HOME", "/home/ana"}})}) {
    EXPECT_EQ(DefaultSessionDatabasePath(env), "/home/ana/.local/share/vesica/sessions.sqlite");
  }
}

TEST(DefaultLocationTest, PasswordDatabaseHomeWhenHomeUnset) {
  const passwd* user = getpwuid(getuid());
  ASSERT_NE(user, nullptr);
  EXPECT_EQ(DefaultSessionDatabasePath(Env({})),
            std::filesystem::path(user->pw_dir) / ".local/share/vesica/sessions.sqlite");
}

TEST(DefaultLocationTest, VesicaRecordsDbOverridesWhenSet) {
  EXPECT_EQ(DefaultSessionStoreLocation(Env({{"VESICA_RECORDS_DB", "host=db dbname=vesica"}, {"HOME", "/h"}})),
            "host=db dbname=vesica");
  EXPECT_EQ(DefaultSessionStoreLocation(Env({{"VESICA_RECORDS_DB", ""}, {"HOME", "/h"}})),
            "/h/.local/share/vesica/sessions.sqlite");
}

TEST(DefaultLocationTest, RealEnvironmentXdgDataHomeGetsAWalDatabase) {
  TempDir dir;
  ScopedEnv env({{"XDG_DATA_HOME", dir.path().string()}, {"VESICA_RECORDS_DB", std::nullopt}});
  const std::string location = DefaultSessionStoreLocation(RealEnv);
  EXPECT_EQ(location, (dir.path() / "vesica" / "sessions.sqlite").string());
  const auto store = OpenSessionStore(location);
  store->Add(SampleRecord(0));
  ASSERT_TRUE(std::filesystem::is_regular_file(dir.path() / "vesica" / "sessions.sqlite"));
  auto* const sqlite = dynamic_cast<SqliteSessionStore*>(store.get());
  ASSERT_NE(sqlite, nullptr);
  EXPECT_EQ(sqlite->JournalMode(), "wal");
}

TEST(DefaultLocationTest, RealEnvironmentFallsBackToHome) {
  TempDir dir;
  ScopedEnv env({{"XDG_DATA_HOME", std::nullopt}, {"HOME", dir.path().string()}, {"VESICA_RECORDS_DB", std::nullopt}});
  EXPECT_EQ(DefaultSessionStoreLocation(), (dir.path() / ".local/share/vesica/sessions.sqlite").string());
  OpenSessionStore(DefaultSessionStoreLocation(RealEnv))->Add(SampleRecord(0));
  EXPECT_TRUE(std::filesystem::is_regular_file(dir.path() / ".local/share/vesica/sessions.sqlite"));
}

}  // namespace
}  // namespace vesica::app
