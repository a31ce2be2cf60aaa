// Sessions that could not be stored wait in the pending file: kept bit for bit, stored at the
// next start, and only those the store still refuses stay.

#include "app/records/pending_sessions.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "tests/records/sample_records.h"
#include "tests/records/temp_dir.h"

namespace vesica::app {
namespace {

using ::testing::HasSubstr;
using testing::SampleRecord;
using testing::TempDir;

TEST(PendingSessionsTest, KeptSessionsReadBackBitForBit) {
  TempDir dir;
  const auto path = dir.path() / "sub" / "sessions.sqlite.pending.csv";
  SessionRecord odd = SampleRecord(4, "ana \"the, first\"");
  odd.scenario = "two\nlines";
  const std::vector<SessionRecord> kept{SampleRecord(0), SampleRecord(3), odd};
  for (const auto& r : kept) KeepPendingSession(path, r);
  EXPECT_EQ(ReadPendingSessions(path), kept);
  EXPECT_TRUE(ReadPendingSessions(dir.path() / "none.csv").empty());
}

TEST(PendingSessionsTest, StoringMovesThemIntoTheStoreAndRemovesTheFile) {
  TempDir dir;
  const std::string db = (dir.path() / "sessions.sqlite").string();
  const auto path = PendingSessionsPath(db);
  EXPECT_EQ(path, db + ".pending.csv");
  KeepPendingSession(path, SampleRecord(0, "ana"));
  KeepPendingSession(path, SampleRecord(1, "ana"));
  const auto store = OpenSessionStore(db);
  const PendingStoreResult r = StorePendingSessions(path, *store);
  EXPECT_EQ(r.stored, 2);
  EXPECT_EQ(r.left, 0);
  EXPECT_FALSE(std::filesystem::exists(path));
  const auto sessions = store->List("ana");
  ASSERT_EQ(sessions.size(), 2u);
  EXPECT_EQ(sessions[1].record, SampleRecord(1, "ana"));
}

TEST(PendingSessionsTest, SessionsTheStoreRefusesStayInTheFile) {
  TempDir dir;
  const auto path = dir.path() / "p.csv";
  SessionRecord bad = SampleRecord(1, "ben");
  bad.ended_unix_s = bad.started_unix_s - 1;
  KeepPendingSession(path, SampleRecord(0, "ana"));
  KeepPendingSession(path, bad);
  const auto store = OpenSessionStore((dir.path() / "s.sqlite").string());
  const PendingStoreResult r = StorePendingSessions(path, *store);
  EXPECT_EQ(r.stored, 1);
  EXPECT_EQ(r.left, 1);
  EXPECT_THAT(r.error, HasSubstr("ended_unix_s"));
  EXPECT_EQ(ReadPendingSessions(path), std::vector<SessionRecord>{bad});
}

TEST(PendingSessionsTest, RowCutShortByAKillIsDroppedAndABadRowNamesItsLine) {
  TempDir dir;
  const auto path = dir.path() / "p.csv";
  KeepPendingSession(path, SampleRecord(0));
  std::ofstream(path, std::ios::app) << "ana,cholecystectomy,station-1,17954";  // no line end
  EXPECT_EQ(ReadPendingSessions(path).size(), 1u);
  KeepPendingSession(path, SampleRecord(1));
  EXPECT_EQ(ReadPendingSessions(path), (std::vector<SessionRecord>{SampleRecord(0), SampleRecord(1)}));
  std::ofstream(path, std::ios::app) << "ana,x,y,notanumber\n";
  try {
    ReadPendingSessions(path);
    FAIL() << "read a bad row";
  } catch (const RecordsError& e) {
    EXPECT_THAT(e.what(), HasSubstr(path.string() + ":4: 4 fields"));
  }
}

}  // namespace
}  // namespace vesica::app
