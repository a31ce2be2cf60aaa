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

// What a build before schema 3 wrote: no procedure column and none of the biopsy metrics.
constexpr const char* kSchema2PendingFile =
    "trainee_id,scenario,station,started_unix_s,ended_unix_s,input_recording_path,replay,unfinished,physics_lag_s,"
    "duration_s,path_length_left_m,path_length_right_m,slips,cautery_on_s,liver_damage_m2,gallbladder_damage_m2,"
    "max_force_N,mean_force_N,tissue_removed_fraction,springs_cut,springs_total,gallbladder_free,perforation,success\n"
    "ana,cholecystectomy,station-1,1795406400,1795406700,,0,1,0.5,300.5,1.25,0.5,2,40,1e-05,0,4.5,0.75,1,210,210,1,0,"
    "1\n";

TEST(PendingSessionsTest, AFileAnOlderBuildLeftReadsAndTakesNewSessionsInItsNewColumns) {
  TempDir dir;
  const auto path = dir.path() / "p.csv";
  std::ofstream(path) << kSchema2PendingFile;
  SessionRecord old;
  old.trainee_id = "ana";
  old.scenario = "cholecystectomy";
  old.station = "station-1";
  old.started_unix_s = 1795406400;
  old.ended_unix_s = 1795406700;
  old.unfinished = true;
  old.physics_lag_s = 0.5;
  old.metrics = {.duration_s = 300.5, .path_length_left_m = 1.25, .path_length_right_m = 0.5, .slips = 2,
                 .cautery_on_s = 40, .liver_damage_m2 = 1e-5, .gallbladder_damage_m2 = 0, .max_force_N = 4.5,
                 .mean_force_N = 0.75, .tissue_removed_fraction = 1, .springs_cut = 210, .springs_total = 210,
                 .gallbladder_free = true, .perforation = false, .success = true};
  EXPECT_EQ(ReadPendingSessions(path), std::vector<SessionRecord>{old});
  // A biopsy kept after it: the file is rewritten in this build's columns, nothing lost.
  const SessionRecord biopsy = SampleRecord(2);
  ASSERT_EQ(biopsy.procedure, Procedure::kNeedleBiopsy);
  KeepPendingSession(path, biopsy);
  EXPECT_EQ(ReadPendingSessions(path), (std::vector<SessionRecord>{old, biopsy}));
  std::ifstream in(path);
  std::string header;
  std::getline(in, header);
  EXPECT_THAT(header, HasSubstr(",physics_lag_s,procedure,duration_s,"));
}

TEST(PendingSessionsTest, AnUnknownColumnOrAProcedureNamesItsLine) {
  TempDir dir;
  const auto path = dir.path() / "p.csv";
  KeepPendingSession(path, SampleRecord(0));
  std::stringstream text;
  text << std::ifstream(path).rdbuf();
  std::string with_bad_procedure = text.str() + text.str().substr(text.str().find('\n') + 1);
  const auto at = with_bad_procedure.rfind(",cholecystectomy,");
  ASSERT_NE(at, std::string::npos);
  with_bad_procedure.replace(at, 17, ",appendectomy,");
  std::ofstream(path) << with_bad_procedure;
  EXPECT_THAT([&] { ReadPendingSessions(path); },
              ::testing::ThrowsMessage<RecordsError>(HasSubstr(":3: procedure: unknown procedure 'appendectomy'")));
  std::ofstream(path) << "trainee_id,colour\nana,red\n";
  EXPECT_THAT([&] { ReadPendingSessions(path); },
              ::testing::ThrowsMessage<RecordsError>(HasSubstr(":2: unknown column 'colour'")));
}

}  // namespace
}  // namespace vesica::app
