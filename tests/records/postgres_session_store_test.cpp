// What only the PostgreSQL backend has: connection strings, whose passwords never reach a
// message, and a server that can go away under a running trainer.

#include "app/records/postgres_session_store.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "app/records/sql_schema.h"
#include "tests/records/postgres_test_server.h"
#include "tests/records/sample_records.h"

namespace vesica::app {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;
using testing::PostgresTestServer;
using testing::SampleRecord;
using ::testing::ThrowsMessage;

TEST(MaskPasswordTest, HidesEveryFormOfPassword) {
  EXPECT_EQ(MaskPassword("postgresql://ana:s3cret@db.example:5432/vesica"),
            "postgresql://ana:***@db.example:5432/vesica");
  EXPECT_EQ(MaskPassword("postgres://ana:s3cret@db/vesica"), "postgres://ana:***@db/vesica");
  EXPECT_EQ(MaskPassword("postgresql://db/vesica?user=ana&password=s3cret&sslmode=require"),
            "postgresql://db/vesica?user=ana&password=***&sslmode=require");
  EXPECT_EQ(MaskPassword("host=db password=s3cret dbname=vesica"), "host=db password=*** dbname=vesica");
  EXPECT_EQ(MaskPassword("host=db password = 's3 cr\\'et' dbname=vesica"), "host=db password = *** dbname=vesica");
}

TEST(MaskPasswordTest, LeavesStringsWithoutPasswordAlone) {
  EXPECT_EQ(MaskPassword("postgresql://ana@db:5432/vesica"), "postgresql://ana@db:5432/vesica");
  EXPECT_EQ(MaskPassword("host=/run/postgresql dbname=vesica"), "host=/run/postgresql dbname=vesica");
}

TEST(PostgresSessionStoreTest, UnreachableServerFailsNamingMaskedLocation) {
  const std::string location = "host=/nonexistent-vesica-socket-dir port=5432 user=ana password=s3cret dbname=vesica";
  EXPECT_THAT([&] { PostgresSessionStore store(location); },
              ThrowsMessage<RecordsError>(AllOf(
                  HasSubstr("session database host=/nonexistent-vesica-socket-dir port=5432 user=ana password=*** "
                            "dbname=vesica: connect: "),
                  Not(HasSubstr("s3cret")))));
}

TEST(PostgresSessionStoreTest, MalformedConnectionStringFailsNamingIt) {
  EXPECT_THAT([] { PostgresSessionStore store("host=db password=s3cret dbname"); },
              ThrowsMessage<RecordsError>(AllOf(HasSubstr("session database host=db password=*** dbname: bad "
                                                          "connection string: "),
                                                Not(HasSubstr("s3cret")))));
  EXPECT_THAT([] { PostgresSessionStore store("postgresql://ana:s3cret@db/vesica?nosuchoption=1"); },
              ThrowsMessage<RecordsError>(AllOf(HasSubstr("postgresql://ana:***@db/vesica?nosuchoption=1: bad "
                                                          "connection string: "),
                                                HasSubstr("nosuchoption"), Not(HasSubstr("s3cret")))));
}

TEST(PostgresSessionStoreTest, ChosenByOpenSessionStoreForAConnectionString) {
  auto& server = PostgresTestServer::Shared();
  ASSERT_TRUE(server.running()) << server.error();
  const std::string location = server.NewDatabase();
  const auto store = OpenSessionStore(location);
  EXPECT_NE(dynamic_cast<PostgresSessionStore*>(store.get()), nullptr);
  store->Add(SampleRecord(0));
  // The rows are in the server's tables, not somewhere else.
  EXPECT_EQ(PostgresTestServer::Query(location, "SELECT count(*) FROM sessions"), "1");
  EXPECT_EQ(PostgresTestServer::Query(location, "SELECT version FROM vesica_schema"),
            std::to_string(kSessionSchemaVersion));
}

TEST(PostgresSessionStoreTest, SchemaVersion3IsMigratedAsSessionsWithoutTheCalotStep) {
  auto& server = PostgresTestServer::Shared();
  ASSERT_TRUE(server.running()) << server.error();
  const std::string location = server.NewDatabase();
  // Version 3 as a build before schema 4 left it, with one cholecystectomy (columns named).
  std::string sql = "BEGIN; CREATE TABLE vesica_schema (version INTEGER NOT NULL);";
  for (const auto& statement : CreateSchemaV1Sql(SqlDialect::kPostgres)) sql += statement + ";";
  for (const auto& statement : MigrateSchemaV1ToV2Sql(SqlDialect::kPostgres)) sql += statement + ";";
  for (const auto& statement : MigrateSchemaV2ToV3Sql(SqlDialect::kPostgres)) sql += statement + ";";
  sql +=
      "INSERT INTO trainees VALUES ('old'); INSERT INTO sessions (trainee_id, scenario, station, started_unix_s, "
      "ended_unix_s, input_recording_path, \"duration_s\", \"path_length_left_m\", \"path_length_right_m\", "
      "\"slips\", \"cautery_on_s\", \"liver_damage_m2\", \"gallbladder_damage_m2\", \"max_force_N\", "
      "\"mean_force_N\", \"tissue_removed_fraction\", \"springs_cut\", \"springs_total\", "
      "\"gallbladder_free\", \"perforation\", \"success\") VALUES ('old', 'cholecystectomy', 'station-1', "
      "1795406400, 1795406700, '', 300.5, 1.25, 0.5, 2, 40, 1e-5, 0, 4.5, 0.75, 1, 210, 210, true, false, true); "
      "INSERT INTO vesica_schema VALUES (3); COMMIT;";
  PostgresTestServer::Query(location, sql);
  const auto store = OpenSessionStore(location);
  EXPECT_EQ(store->SchemaVersion(), 4);
  const auto old = store->List("old");
  ASSERT_EQ(old.size(), 1u);
  EXPECT_EQ(old[0].record.metrics.duration_s, 300.5);
  EXPECT_TRUE(old[0].record.metrics.success);
  EXPECT_FALSE(old[0].record.metrics.calot_step);
  EXPECT_EQ(old[0].record.metrics.bile_duct_injuries, 0);
  const SessionRecord calot = SampleRecord(4, "old");
  ASSERT_TRUE(calot.metrics.calot_step);
  const auto id = store->Add(calot);
  EXPECT_EQ(store->Get(id)->record, calot);
  EXPECT_EQ(store->CheckIntegrity(), "ok");
}

TEST(PostgresSessionStoreTest, ServerGoneFailsEachCallWithRecordsError) {
  PostgresTestServer server;  // its own: this test stops it
  ASSERT_TRUE(server.running()) << server.error();
  const std::string location = server.NewDatabase();
  PostgresSessionStore store(location);
  store.Add(SampleRecord(0));
  server.Stop();
  EXPECT_THAT([&] { store.Add(SampleRecord(1)); },
              ThrowsMessage<RecordsError>(HasSubstr("session database " + location)));
  EXPECT_THAT([&] { store.List("trainee-7"); }, ThrowsMessage<RecordsError>(HasSubstr("list sessions")));
  EXPECT_THAT([&] { store.CheckIntegrity(); }, ThrowsMessage<RecordsError>(HasSubstr("session database " + location)));
}

}  // namespace
}  // namespace vesica::app
