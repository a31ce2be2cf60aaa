// The checklist every SessionStore backend passes, run once on SQLite and once on PostgreSQL.

#include "app/records/session_store.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <variant>

#include "app/records/metric_fields.h"
#include "tests/records/sample_records.h"
#include "tests/records/store_test_fixture.h"

namespace vesica::app {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using testing::SampleRecord;
using testing::StoreTest;

std::vector<std::int64_t> Ids(const std::vector<StoredSession>& sessions) {
  std::vector<std::int64_t> ids;
  for (const auto& s : sessions) ids.push_back(s.id);
  return ids;
}

// Compares field by field so that a failure names the column that did not round-trip.
void ExpectSameRecord(const SessionRecord& stored, const SessionRecord& expected) {
  EXPECT_EQ(stored.trainee_id, expected.trainee_id);
  EXPECT_EQ(stored.scenario, expected.scenario);
  EXPECT_EQ(stored.station, expected.station);
  EXPECT_EQ(stored.started_unix_s, expected.started_unix_s);
  EXPECT_EQ(stored.ended_unix_s, expected.ended_unix_s);
  EXPECT_EQ(stored.input_recording_path, expected.input_recording_path);
  for (const auto& field : kMetricFields) {
    std::visit(
        [&](auto member) {
          // Bit-exact for doubles: EXPECT_EQ, not EXPECT_DOUBLE_EQ.
          EXPECT_EQ(stored.metrics.*member, expected.metrics.*member) << "metric " << field.name;
        },
        field.member);
  }
  EXPECT_TRUE(stored == expected);
}

TEST_P(StoreTest, AddThenGetRoundTripsEveryFieldExactly) {
  const auto store = OpenSessionStore(backend_.NewLocation());
  const SessionRecord record = SampleRecord(4);
  const std::int64_t id = store->Add(record);
  const auto stored = store->Get(id);
  ASSERT_TRUE(stored.has_value());
  EXPECT_EQ(stored->id, id);
  ExpectSameRecord(stored->record, record);
}

TEST_P(StoreTest, ExtremeValuesRoundTripExactly) {
  const auto store = OpenSessionStore(backend_.NewLocation());
  SessionRecord record = SampleRecord(1, "trainée, \"quoted\"\nnew line ✓");
  record.scenario = "";
  record.station = std::string(2000, 's');
  record.input_recording_path = "";
  record.started_unix_s = 0;
  record.ended_unix_s = std::numeric_limits<std::int64_t>::max();
  record.metrics.duration_s = std::numeric_limits<double>::max();
  record.metrics.path_length_left_m = std::numeric_limits<double>::denorm_min();
  record.metrics.path_length_right_m = 0.1 + 0.2;
  record.metrics.liver_damage_m2 = 0;
  record.metrics.tissue_removed_fraction = std::nextafter(1.0, 0.0);
  record.metrics.slips = std::numeric_limits<int>::max();
  record.metrics.springs_total = 0;
  const std::int64_t id = store->Add(record);
  const auto stored = store->Get(id);
  ASSERT_TRUE(stored.has_value());
  ExpectSameRecord(stored->record, record);
}

TEST_P(StoreTest, GetOfUnknownIdIsEmpty) {
  const auto store = OpenSessionStore(backend_.NewLocation());
  const std::int64_t id = store->Add(SampleRecord(0));
  EXPECT_FALSE(store->Get(id + 1).has_value());
  EXPECT_FALSE(store->Get(-1).has_value());
}

TEST_P(StoreTest, AddGivesIncreasingIds) {
  const auto store = OpenSessionStore(backend_.NewLocation());
  const std::int64_t a = store->Add(SampleRecord(0));
  const std::int64_t b = store->Add(SampleRecord(1));
  const std::int64_t c = store->Add(SampleRecord(2));
  EXPECT_LT(a, b);
  EXPECT_LT(b, c);
}

TEST_P(StoreTest, ListIsTheTraineesSessionsOldestFirstTiesById) {
  const auto store = OpenSessionStore(backend_.NewLocation());
  // Added out of order, with another trainee in between and two sessions starting together.
  const std::int64_t third = store->Add(SampleRecord(5, "ana"));
  store->Add(SampleRecord(1, "ben"));
  const std::int64_t first = store->Add(SampleRecord(2, "ana"));
  SessionRecord same_start = SampleRecord(9, "ana");
  same_start.started_unix_s = SampleRecord(5).started_unix_s;
  const std::int64_t fourth = store->Add(same_start);
  const std::int64_t second = store->Add(SampleRecord(3, "ana"));

  const auto sessions = store->List("ana");
  EXPECT_THAT(Ids(sessions), ElementsAre(first, second, third, fourth));
  ASSERT_EQ(sessions.size(), 4u);
  ExpectSameRecord(sessions[0].record, SampleRecord(2, "ana"));
  ExpectSameRecord(sessions[3].record, same_start);
  EXPECT_EQ(store->List("ben").size(), 1u);
}

TEST_P(StoreTest, ListOfUnknownTraineeIsEmpty) {
  const auto store = OpenSessionStore(backend_.NewLocation());
  store->Add(SampleRecord(0, "ana"));
  EXPECT_TRUE(store->List("nobody").empty());
  EXPECT_TRUE(store->List("ANA").empty());  // ids are case-sensitive
}

TEST_P(StoreTest, ListTraineesIsSortedAndDistinct) {
  const auto store = OpenSessionStore(backend_.NewLocation());
  EXPECT_TRUE(store->ListTrainees().empty());
  for (const char* trainee : {"zoe", "Bob", "ana", "zoe", "ana", "bob"}) store->Add(SampleRecord(0, trainee));
  // Byte order in both backends (upper case before lower case), whatever the server's locale.
  EXPECT_THAT(store->ListTrainees(), ElementsAre("Bob", "ana", "bob", "zoe"));
}

struct BadRecordCase {
  const char* what;  // substring the message must contain
  std::function<void(SessionRecord&)> spoil;
};

TEST_P(StoreTest, InvalidRecordIsRefusedNamingLocationAndFieldAndNothingIsStored) {
  const std::string location = backend_.NewLocation();
  const auto store = OpenSessionStore(location);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const BadRecordCase cases[] = {
      {"trainee_id: must not be empty", [](SessionRecord& r) { r.trainee_id.clear(); }},
      {"ended_unix_s", [](SessionRecord& r) { r.ended_unix_s = r.started_unix_s - 1; }},
      {"metrics.duration_s", [&](SessionRecord& r) { r.metrics.duration_s = nan; }},
      {"metrics.max_force_N", [&](SessionRecord& r) { r.metrics.max_force_N = inf; }},
      {"metrics.liver_damage_m2", [](SessionRecord& r) { r.metrics.liver_damage_m2 = -1e-9; }},
      {"metrics.slips", [](SessionRecord& r) { r.metrics.slips = -1; }},
      {"metrics.springs_total", [](SessionRecord& r) { r.metrics.springs_total = -3; }},
      {"scenario: contains a NUL", [](SessionRecord& r) { r.scenario = std::string("a\0b", 3); }},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    SessionRecord record = SampleRecord(0, "eve");
    c.spoil(record);
    try {
      store->Add(record);
      ADD_FAILURE() << "Add accepted a record with a bad " << c.what;
    } catch (const RecordsError& error) {
      EXPECT_THAT(error.what(), HasSubstr(c.what));
      EXPECT_THAT(error.what(), HasSubstr(store->Describe()));
      EXPECT_THAT(error.what(), HasSubstr("add session"));
    }
  }
  EXPECT_TRUE(store->List("eve").empty());
  EXPECT_TRUE(store->ListTrainees().empty());
  EXPECT_EQ(store->CheckIntegrity(), "ok");
}

TEST_P(StoreTest, DescribeNamesTheLocation) {
  const std::string location = backend_.NewLocation();
  const auto store = OpenSessionStore(location);
  EXPECT_EQ(store->Describe(), location);  // test locations carry no password
}

TEST_P(StoreTest, NewStoreHasCurrentSchemaAndPassesIntegrityCheck) {
  const auto store = OpenSessionStore(backend_.NewLocation());
  EXPECT_EQ(store->SchemaVersion(), kSessionSchemaVersion);
  EXPECT_EQ(store->CheckIntegrity(), "ok");
  store->Add(SampleRecord(0));
  EXPECT_EQ(store->CheckIntegrity(), "ok");
}

TEST_P(StoreTest, ReopeningKeepsEverySession) {
  const std::string location = backend_.NewLocation();
  std::vector<SessionRecord> added;
  {
    const auto store = OpenSessionStore(location);
    for (int i = 0; i < 3; ++i) {
      added.push_back(SampleRecord(i));
      store->Add(added.back());
    }
  }
  const auto reopened = OpenSessionStore(location);
  EXPECT_EQ(reopened->SchemaVersion(), kSessionSchemaVersion);
  const auto sessions = reopened->List("trainee-7");
  ASSERT_EQ(sessions.size(), 3u);
  for (int i = 0; i < 3; ++i) ExpectSameRecord(sessions[i].record, added[i]);
  EXPECT_EQ(reopened->CheckIntegrity(), "ok");
}

TEST_P(StoreTest, TwoOpenStoresOnOneLocationSeeEachOthersSessions) {
  // Two stations on one server, or the trainer and vesica-records on one file.
  const std::string location = backend_.NewLocation();
  const auto a = OpenSessionStore(location);
  const auto b = OpenSessionStore(location);
  const std::int64_t from_a = a->Add(SampleRecord(0));
  const std::int64_t from_b = b->Add(SampleRecord(1));
  EXPECT_THAT(Ids(a->List("trainee-7")), ElementsAre(from_a, from_b));
  EXPECT_THAT(Ids(b->List("trainee-7")), ElementsAre(from_a, from_b));
}

TEST_P(StoreTest, NewerSchemaIsRefusedNamingLocationAndVersion) {
  const std::string location = backend_.NewLocation();
  OpenSessionStore(location)->Add(SampleRecord(0));
  backend_.SetSchemaVersion(location, kSessionSchemaVersion + 1);
  try {
    OpenSessionStore(location);
    FAIL() << "opened a store with schema version " << kSessionSchemaVersion + 1;
  } catch (const RecordsError& error) {
    EXPECT_THAT(error.what(), HasSubstr(location));
    EXPECT_THAT(error.what(), HasSubstr("schema version " + std::to_string(kSessionSchemaVersion + 1)));
    EXPECT_THAT(error.what(), HasSubstr("newer"));
  }
  // Refusing must not have changed it: back at our version, the session is still there.
  backend_.SetSchemaVersion(location, kSessionSchemaVersion);
  EXPECT_EQ(OpenSessionStore(location)->List("trainee-7").size(), 1u);
}

INSTANTIATE_TEST_SUITE_P(Backends, StoreTest, ::testing::Values("sqlite", "postgres"), testing::BackendName);

TEST(IsConnectionStringTest, TellsConnectionStringsFromPaths) {
  EXPECT_TRUE(IsConnectionString("postgresql://user@db.example:5432/vesica"));
  EXPECT_TRUE(IsConnectionString("postgres://db/vesica"));
  EXPECT_TRUE(IsConnectionString("host=/run/postgresql dbname=vesica"));
  EXPECT_TRUE(IsConnectionString("  dbname = vesica"));
  EXPECT_FALSE(IsConnectionString("/var/lib/vesica/sessions.sqlite"));
  EXPECT_FALSE(IsConnectionString("sessions.sqlite"));
  EXPECT_FALSE(IsConnectionString("./host=x.sqlite"));
  EXPECT_FALSE(IsConnectionString("C:/data/a=b"));
}

TEST(OpenSessionStoreTest, EmptyLocationIsAnError) {
  EXPECT_THAT([] { OpenSessionStore(""); }, ::testing::ThrowsMessage<RecordsError>(HasSubstr("empty location")));
}

TEST(ValidateRecordTest, AcceptsASampleAndZeroMetrics) {
  EXPECT_NO_THROW(ValidateRecord(SampleRecord(0)));
  SessionRecord zero;
  zero.trainee_id = "t";
  EXPECT_NO_THROW(ValidateRecord(zero));
}

TEST(ValidateRecordTest, MessageNamesTraineeAndField) {
  SessionRecord record = SampleRecord(0, "dora");
  record.metrics.cautery_on_s = -2;
  EXPECT_THAT([&] { ValidateRecord(record); },
              ::testing::ThrowsMessage<RecordsError>(
                  HasSubstr("session record of trainee 'dora': metrics.cautery_on_s: must be finite and >= 0")));
}

}  // namespace
}  // namespace vesica::app
