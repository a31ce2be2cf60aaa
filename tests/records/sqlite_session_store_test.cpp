// What only the SQLite backend promises: a WAL-mode file, created with its folders, and clear
// errors for locations that cannot hold a database.

#include "app/records/sqlite_session_store.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <fstream>
#include <sstream>

#include "app/records/sql_schema.h"
#include "tests/records/sample_records.h"
#include "tests/records/temp_dir.h"

namespace vesica::app {
namespace {

using ::testing::HasSubstr;
using testing::SampleRecord;
using testing::TempDir;
using ::testing::ThrowsMessage;

std::string ReadBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

void WriteBytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// Runs `sql` on the file with SQLite itself (no store): to build old or odd databases.
void RawSql(const std::filesystem::path& path, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  char* error = nullptr;
  const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error);
  EXPECT_EQ(rc, SQLITE_OK) << (error ? error : "");
  sqlite3_free(error);
  sqlite3_close(db);
}

// A version-1 database as a build before schema 2 left it, with one session of trainee "old".
void WriteSchemaV1Database(const std::filesystem::path& path) {
  std::string sql = "BEGIN;";
  for (const auto& statement : CreateSchemaV1Sql(SqlDialect::kSqlite)) sql += statement + ";";
  sql += "INSERT INTO trainees VALUES ('old');";
  sql +=
      "INSERT INTO sessions VALUES (1, 'old', 'cholecystectomy', 'station-1', 1795406400, 1795406700, '', "
      "300.5, 1.25, 0.5, 2, 40, 1e-5, 0, 4.5, 0.75, 1, 210, 210, 1, 0, 1);";
  sql += "PRAGMA user_version=1; COMMIT;";
  RawSql(path, sql);
}

TEST(SqliteSessionStoreTest, SchemaVersion1IsMigratedKeepingItsSessions) {
  TempDir dir;
  const auto path = dir.path() / "sessions.sqlite";
  WriteSchemaV1Database(path);
  SqliteSessionStore store(path);
  EXPECT_EQ(store.SchemaVersion(), kSessionSchemaVersion);
  const auto old = store.List("old");
  ASSERT_EQ(old.size(), 1u);
  EXPECT_EQ(old[0].record.metrics.duration_s, 300.5);
  EXPECT_TRUE(old[0].record.metrics.success);
  EXPECT_FALSE(old[0].record.replay);  // sessions before version 2 were all the trainees' own
  EXPECT_FALSE(old[0].record.unfinished);
  EXPECT_EQ(old[0].record.physics_lag_s, 0.0);
  SessionRecord replay = SampleRecord(3, "old");
  ASSERT_TRUE(replay.replay);
  const auto id = store.Add(replay);
  EXPECT_EQ(store.Get(id)->record, replay);
  EXPECT_EQ(store.CheckIntegrity(), "ok");
}

// A version-2 database as a build before schema 3 left it: one session of trainee "old", a replay.
void WriteSchemaV2Database(const std::filesystem::path& path) {
  std::string sql = "BEGIN;";
  for (const auto& statement : CreateSchemaV1Sql(SqlDialect::kSqlite)) sql += statement + ";";
  for (const auto& statement : MigrateSchemaV1ToV2Sql(SqlDialect::kSqlite)) sql += statement + ";";
  sql += "INSERT INTO trainees VALUES ('old');";
  sql +=
      "INSERT INTO sessions VALUES (1, 'old', 'cholecystectomy', 'station-1', 1795406400, 1795406700, '', "
      "300.5, 1.25, 0.5, 2, 40, 1e-5, 0, 4.5, 0.75, 1, 210, 210, 1, 0, 1, 1, 0, 2.5);";
  sql += "PRAGMA user_version=2; COMMIT;";
  RawSql(path, sql);
}

TEST(SqliteSessionStoreTest, SchemaVersion2IsMigratedAsCholecystectomiesWithNoBiopsyMetrics) {
  TempDir dir;
  const auto path = dir.path() / "sessions.sqlite";
  WriteSchemaV2Database(path);
  SqliteSessionStore store(path);
  EXPECT_EQ(store.SchemaVersion(), kSessionSchemaVersion);
  const auto old = store.List("old");
  ASSERT_EQ(old.size(), 1u);
  const SessionRecord& r = old[0].record;
  EXPECT_EQ(r.procedure, Procedure::kCholecystectomy);
  EXPECT_TRUE(r.replay);
  EXPECT_EQ(r.physics_lag_s, 2.5);
  EXPECT_EQ(r.metrics.max_force_N, 4.5);
  EXPECT_FALSE(r.metrics.biopsy_sampled);
  EXPECT_EQ(r.metrics.time_to_sample_s, 0.0);
  EXPECT_EQ(r.metrics.insertion_attempts, 0);
  // A biopsy goes in beside it and reads back whole.
  SessionRecord biopsy = SampleRecord(2, "old");
  ASSERT_EQ(biopsy.procedure, Procedure::kNeedleBiopsy);
  const auto id = store.Add(biopsy);
  EXPECT_EQ(store.Get(id)->record, biopsy);
  EXPECT_EQ(store.CheckIntegrity(), "ok");
}

// A version-3 database as a build before schema 4 left it: a cholecystectomy and a biopsy of
// trainee "old", with the columns of version 3 named (so the test does not depend on their order).
void WriteSchemaV3Database(const std::filesystem::path& path) {
  std::string sql = "BEGIN;";
  for (const auto& statement : CreateSchemaV1Sql(SqlDialect::kSqlite)) sql += statement + ";";
  for (const auto& statement : MigrateSchemaV1ToV2Sql(SqlDialect::kSqlite)) sql += statement + ";";
  for (const auto& statement : MigrateSchemaV2ToV3Sql(SqlDialect::kSqlite)) sql += statement + ";";
  sql += "INSERT INTO trainees VALUES ('old');";
  const std::string columns =
      "(id, trainee_id, scenario, station, started_unix_s, ended_unix_s, input_recording_path, replay, unfinished, "
      "physics_lag_s, procedure, duration_s, path_length_left_m, path_length_right_m, slips, cautery_on_s, "
      "liver_damage_m2, gallbladder_damage_m2, max_force_N, mean_force_N, tissue_removed_fraction, springs_cut, "
      "springs_total, gallbladder_free, perforation, success, biopsy_sampled, time_to_sample_s, sample_distance_m, "
      "nogo_crossings, insertion_attempts)";
  sql += "INSERT INTO sessions " + columns +
         " VALUES (1, 'old', 'cholecystectomy', 'station-1', 1795406400, 1795406700, '', 0, 0, 0.5, "
         "'cholecystectomy', 300.5, 1.25, 0.5, 2, 40, 1e-5, 0, 4.5, 0.75, 1, 210, 210, 1, 0, 1, 0, 0, 0, 0, 0);";
  sql += "INSERT INTO sessions " + columns +
         " VALUES (2, 'old', 'needle-biopsy-0', 'station-1', 1795407000, 1795407100, '', 0, 0, 0, "
         "'needle_biopsy', 100, 0, 0, 0, 0, 0, 0, 2.5, 1.5, 0, 0, 0, 0, 0, 1, 1, 95.5, 0.007, 1, 2);";
  sql += "PRAGMA user_version=3; COMMIT;";
  RawSql(path, sql);
}

TEST(SqliteSessionStoreTest, SchemaVersion3IsMigratedAsSessionsWithoutTheCalotStep) {
  TempDir dir;
  const auto path = dir.path() / "sessions.sqlite";
  WriteSchemaV3Database(path);
  SqliteSessionStore store(path);
  EXPECT_EQ(store.SchemaVersion(), 4);
  EXPECT_EQ(SqliteSessionStore(path, StoreAccess::kReadOnly).SchemaVersion(), 4);  // the file says so too
  const auto old = store.List("old");
  ASSERT_EQ(old.size(), 2u);
  const SessionMetrics& chole = old[0].record.metrics;
  EXPECT_EQ(old[0].record.procedure, Procedure::kCholecystectomy);
  EXPECT_EQ(chole.duration_s, 300.5);
  EXPECT_EQ(chole.springs_cut, 210);
  EXPECT_TRUE(chole.success);
  EXPECT_FALSE(chole.calot_step);
  EXPECT_FALSE(chole.cvs_achieved);
  EXPECT_EQ(chole.cvs_time_s, 0.0);
  EXPECT_EQ(chole.bile_duct_injuries, 0);
  EXPECT_FALSE(chole.calot_passed);
  EXPECT_EQ(old[1].record.procedure, Procedure::kNeedleBiopsy);
  EXPECT_EQ(old[1].record.metrics.sample_distance_m, 0.007);
  EXPECT_EQ(old[1].record.metrics.insertion_attempts, 2);
  // A session with the Calot step goes in beside them and reads back whole.
  SessionRecord calot = SampleRecord(4, "old");
  ASSERT_TRUE(calot.metrics.calot_step);
  const auto id = store.Add(calot);
  EXPECT_EQ(store.Get(id)->record, calot);
  EXPECT_EQ(store.CheckIntegrity(), "ok");
}

TEST(SqliteSessionStoreTest, ReadOnlyOpenOfVersion3ReadsItsSessionsWithoutTheCalotStep) {
  TempDir dir;
  const auto path = dir.path() / "sessions.sqlite";
  WriteSchemaV3Database(path);
  const std::string before = ReadBytes(path);
  {
    SqliteSessionStore store(path, StoreAccess::kReadOnly);
    EXPECT_EQ(store.SchemaVersion(), 3);
    const auto old = store.List("old");
    ASSERT_EQ(old.size(), 2u);
    EXPECT_FALSE(old[0].record.metrics.calot_step);
    EXPECT_EQ(old[0].record.metrics.bleeding_events, 0);
    EXPECT_EQ(old[0].record.metrics.max_force_N, 4.5);
  }
  EXPECT_EQ(ReadBytes(path), before);
}

TEST(SqliteSessionStoreTest, AProcedureThisBuildDoesNotKnowIsRefusedByTheTable) {
  TempDir dir;
  const auto path = dir.path() / "sessions.sqlite";
  { SqliteSessionStore store(path); }
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  const int rc = sqlite3_exec(db,
                              "INSERT INTO trainees VALUES ('x'); INSERT INTO sessions (trainee_id, scenario, station, "
                              "started_unix_s, ended_unix_s, input_recording_path, procedure, duration_s, "
                              "path_length_left_m, path_length_right_m, slips, cautery_on_s, liver_damage_m2, "
                              "gallbladder_damage_m2, max_force_N, mean_force_N, tissue_removed_fraction, springs_cut, "
                              "springs_total, gallbladder_free, perforation, success) VALUES ('x', 's', 't', 0, 0, '', "
                              "'appendectomy', 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0)",
                              nullptr, nullptr, nullptr);
  sqlite3_close(db);
  EXPECT_EQ(rc & 0xff, SQLITE_CONSTRAINT);
}

TEST(SqliteSessionStoreTest, ReadOnlyOpenOfVersion2ReadsItsSessionsAsCholecystectomies) {
  TempDir dir;
  const auto path = dir.path() / "sessions.sqlite";
  WriteSchemaV2Database(path);
  const std::string before = ReadBytes(path);
  {
    SqliteSessionStore store(path, StoreAccess::kReadOnly);
    EXPECT_EQ(store.SchemaVersion(), 2);
    const auto old = store.List("old");
    ASSERT_EQ(old.size(), 1u);
    EXPECT_EQ(old[0].record.procedure, Procedure::kCholecystectomy);
    EXPECT_EQ(old[0].record.metrics.nogo_crossings, 0);
    EXPECT_TRUE(old[0].record.metrics.success);
  }
  EXPECT_EQ(ReadBytes(path), before);
}

TEST(SqliteSessionStoreTest, ReadOnlyOpenChangesNothingInTheFile) {
  // A version-1 database in rollback-journal mode: opening it to read must neither switch it to
  // WAL nor migrate it (the trainer that owns it does that), and must read its sessions.
  TempDir dir;
  const auto path = dir.path() / "sessions.sqlite";
  WriteSchemaV1Database(path);
  const std::string before = ReadBytes(path);
  {
    SqliteSessionStore store(path, StoreAccess::kReadOnly);
    EXPECT_EQ(store.SchemaVersion(), 1);
    EXPECT_EQ(store.ListTrainees(), std::vector<std::string>{"old"});
    const auto old = store.List("old");
    ASSERT_EQ(old.size(), 1u);
    EXPECT_EQ(old[0].record.metrics.max_force_N, 4.5);
    EXPECT_FALSE(old[0].record.replay);
    EXPECT_THAT([&] { store.Add(SampleRecord(0)); }, ThrowsMessage<RecordsError>(HasSubstr("opened read-only")));
  }
  EXPECT_EQ(ReadBytes(path), before);
  EXPECT_FALSE(std::filesystem::exists(path.string() + "-wal"));
}

TEST(SqliteSessionStoreTest, ReadOnlyOpenOfAMissingFileCreatesNothing) {
  TempDir dir;
  const auto path = dir.path() / "sub" / "sessions.sqlite";
  EXPECT_THAT([&] { SqliteSessionStore store(path, StoreAccess::kReadOnly); },
              ThrowsMessage<RecordsError>(HasSubstr(path.string() + ": no such file")));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "sub"));
}

TEST(SqliteSessionStoreTest, UsesWalJournal) {
  TempDir dir;
  const auto path = dir.path() / "sessions.sqlite";
  SqliteSessionStore store(path);
  EXPECT_EQ(store.JournalMode(), "wal");
  store.Add(SampleRecord(0));
  // The file header says so too (bytes 18 and 19, read/write format: 1 rollback, 2 WAL), and
  // the committed session sits in the -wal file until a checkpoint.
  const std::string header = ReadBytes(path).substr(0, 20);
  ASSERT_EQ(header.substr(0, 16), std::string("SQLite format 3\0", 16));
  EXPECT_EQ(header[18], 2);
  EXPECT_EQ(header[19], 2);
  EXPECT_GT(std::filesystem::file_size(path.string() + "-wal"), 0u);
}

TEST(SqliteSessionStoreTest, CreatesMissingFolders) {
  TempDir dir;
  const auto path = dir.path() / "a" / "b" / "sessions.sqlite";
  SqliteSessionStore(path).Add(SampleRecord(0));
  EXPECT_TRUE(std::filesystem::is_regular_file(path));
  EXPECT_EQ(SqliteSessionStore(path).List("trainee-7").size(), 1u);
}

TEST(SqliteSessionStoreTest, FolderThatIsAFileFailsNamingPathAndStep) {
  TempDir dir;
  WriteBytes(dir.path() / "plain-file", "x");
  const auto path = dir.path() / "plain-file" / "sessions.sqlite";
  EXPECT_THAT([&] { SqliteSessionStore store(path); },
              ThrowsMessage<RecordsError>(HasSubstr("session database " + path.string() + ": cannot create folder")));
}

TEST(SqliteSessionStoreTest, DirectoryAsDatabaseFails) {
  TempDir dir;
  EXPECT_THAT([&] { SqliteSessionStore store(dir.path()); },
              ThrowsMessage<RecordsError>(HasSubstr(dir.path().string() + ": is a directory")));
}

TEST(SqliteSessionStoreTest, FileThatIsNotADatabaseFailsAndIsLeftAlone) {
  TempDir dir;
  const auto path = dir.path() / "notes.txt";
  const std::string text(5000, 'n');
  WriteBytes(path, text);
  EXPECT_THAT([&] { SqliteSessionStore store(path); },
              ThrowsMessage<RecordsError>(HasSubstr("session database " + path.string() +
                                                    ": switch to WAL journal: "
                                                    "file is not a database")));
  EXPECT_EQ(ReadBytes(path), text);
}

TEST(SqliteSessionStoreTest, CorruptDatabaseFailsOnOpen) {
  TempDir dir;
  const auto path = dir.path() / "sessions.sqlite";
  {
    SqliteSessionStore store(path);
    for (int i = 0; i < 40; ++i) store.Add(SampleRecord(i));
  }  // closing the last connection checkpoints the WAL into the file
  std::string bytes = ReadBytes(path);
  ASSERT_GT(bytes.size(), 3 * 4096u);
  // Scribble over the second page onwards (the first table's pages), keeping the header.
  for (std::size_t i = 4096; i < bytes.size(); i += 7) bytes[i] = static_cast<char>(0xA5);
  WriteBytes(path, bytes);
  try {
    SqliteSessionStore store(path);
    FAIL() << "opened a corrupt database";
  } catch (const RecordsError& error) {
    EXPECT_THAT(error.what(), HasSubstr("session database " + path.string() + ": "));
    EXPECT_THAT(error.what(), ::testing::ContainsRegex("corrupt|malformed"));
  }
}

}  // namespace
}  // namespace vesica::app
