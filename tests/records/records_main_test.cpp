// vesica-records run as a user runs it: a separate process, its output and exit status.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "app/records/session_store.h"
#include "tests/records/csv_reader.h"
#include "tests/records/postgres_test_server.h"
#include "tests/records/run_process.h"
#include "tests/records/sample_records.h"
#include "tests/records/temp_dir.h"

namespace vesica::app {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;
using testing::ProcessResult;
using testing::SampleRecord;
using ::testing::StartsWith;
using testing::TempDir;

// The tool with these arguments, with neither VESICA_RECORDS_DB nor XDG_DATA_HOME from the
// caller's environment, so that no test ever reads or writes the user's real sessions.
ProcessResult Records(std::vector<std::string> args, std::map<std::string, std::optional<std::string>> env = {}) {
  args.insert(args.begin(), VESICA_RECORDS_EXE);
  env.try_emplace("VESICA_RECORDS_DB", std::nullopt);
  env.try_emplace("XDG_DATA_HOME", "/nonexistent-vesica-test-xdg");
  return testing::RunProcess(args, env);
}

class RecordsToolTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto store = OpenSessionStore(db_);
    ids_.push_back(store->Add(SampleRecord(2, "ana")));
    ids_.push_back(store->Add(SampleRecord(0, "ana")));
    ids_.push_back(store->Add(SampleRecord(1, "ben")));
  }

  TempDir dir_;
  std::string db_ = (dir_.path() / "sessions.sqlite").string();
  std::vector<std::int64_t> ids_;
};

TEST_F(RecordsToolTest, ListPrintsTheTrainees) {
  const auto run = Records({"--db", db_, "list"});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.out, "ana\nben\n");
  EXPECT_EQ(run.err, "");
}

TEST_F(RecordsToolTest, ListTraineePrintsSessionsOldestFirst) {
  const auto run = Records({"--db", db_, "list", "--trainee", "ana"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::istringstream out(run.out);
  std::vector<std::string> lines;
  for (std::string line; std::getline(out, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 3u) << run.out;
  // The units of the trainer and the CSV export, named in the header: seconds, not minutes.
  EXPECT_THAT(lines[0], AllOf(StartsWith("id"), HasSubstr("started (UTC)"), HasSubstr("duration (s)"),
                              HasSubstr("success")));
  // SampleRecord(0): 2026-11-23T04:00:00Z, 300.08 s, free and no perforation.
  EXPECT_THAT(lines[1],
              AllOf(StartsWith(std::to_string(ids_[1]) + " "), HasSubstr("ana"), HasSubstr("2026-11-23T04:00:00Z"),
                    HasSubstr(" 300.1 "), HasSubstr("yes"), HasSubstr("cholecystectomy-0")));
  // SampleRecord(2), ten minutes later per index: free and no perforation too.
  EXPECT_THAT(lines[2], HasSubstr(" yes "));
  EXPECT_THAT(lines[2], AllOf(StartsWith(std::to_string(ids_[0]) + " "), HasSubstr("2026-11-23T04:20:00Z")));
}

TEST_F(RecordsToolTest, ListNeverShowsAReplayOrAnUnfinishedSessionAsASuccess) {
  SessionRecord replay = SampleRecord(0, "cy"), unfinished = SampleRecord(2, "cy");
  ASSERT_TRUE(replay.metrics.success && unfinished.metrics.success);
  replay.replay = true;
  unfinished.unfinished = true;
  const auto store = OpenSessionStore(db_);
  store->Add(replay);
  store->Add(unfinished);
  const auto run = Records({"--db", db_, "list", "--trainee", "cy"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, AllOf(HasSubstr(" replay "), HasSubstr(" unfinished "), Not(HasSubstr(" yes "))));
}

TEST_F(RecordsToolTest, ExportCsvWritesTheSameAsTheLibrary) {
  std::ostringstream expected;
  OpenSessionStore(db_)->ExportCsv("ana", expected);

  const auto to_stdout = Records({"--db", db_, "export-csv", "--trainee", "ana"});
  ASSERT_EQ(to_stdout.exit_code, 0) << to_stdout.err;
  EXPECT_EQ(to_stdout.out, expected.str());
  const auto rows = testing::ReadCsv(to_stdout.out);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[1][0], std::to_string(ids_[1]));
  EXPECT_EQ(rows[2][0], std::to_string(ids_[0]));

  const std::string file = (dir_.path() / "ana.csv").string();
  const auto to_file = Records({"--db", db_, "export-csv", "--trainee", "ana", "-o", file});
  ASSERT_EQ(to_file.exit_code, 0) << to_file.err;
  EXPECT_EQ(to_file.out, "");
  std::stringstream written;
  written << std::ifstream(file).rdbuf();
  EXPECT_EQ(written.str(), expected.str());
}

TEST_F(RecordsToolTest, DefaultLocationIsXdgDataHome) {
  const TempDir xdg;
  std::filesystem::create_directories(xdg.path() / "vesica");
  std::filesystem::copy_file(db_, xdg.path() / "vesica" / "sessions.sqlite");
  const auto run = Records({"list"}, {{"XDG_DATA_HOME", xdg.path().string()}});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.out, "ana\nben\n");
}

TEST_F(RecordsToolTest, VesicaRecordsDbOverridesTheDefault) {
  const auto run = Records({"list"}, {{"VESICA_RECORDS_DB", db_}});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.out, "ana\nben\n");
}

TEST_F(RecordsToolTest, MissingDatabaseFailsNamingItAndCreatesNothing) {
  const std::string missing = (dir_.path() / "typo.sqlite").string();
  const auto run = Records({"--db", missing, "list"});
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_EQ(run.out, "");
  EXPECT_THAT(run.err, HasSubstr("vesica-records: session database " + missing + ": no such file"));
  EXPECT_FALSE(std::filesystem::exists(missing));
}

TEST_F(RecordsToolTest, FileThatIsNotADatabaseFails) {
  const std::string notes = (dir_.path() / "notes.txt").string();
  std::ofstream(notes) << std::string(3000, 'n');
  const auto run = Records({"--db", notes, "export-csv", "--trainee", "ana"});
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_EQ(run.out, "");
  EXPECT_THAT(run.err, HasSubstr("session database " + notes + ": check database: file is not a database"));
}

TEST_F(RecordsToolTest, ReadsADatabaseItCannotWrite) {
  // Another user's database (a station's copy, a backup on a read-only disk): as "nobody", with
  // the file and its folder read-only, listing and exporting work and leave no trace.
  namespace fs = std::filesystem;
  fs::permissions(dir_.path(), fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                                   fs::perms::others_read | fs::perms::others_exec);
  fs::permissions(db_, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  const std::string before = [&] {
    std::stringstream bytes;
    bytes << std::ifstream(db_, std::ios::binary).rdbuf();
    return bytes.str();
  }();
  fs::permissions(dir_.path(), fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                                   fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec);
  const auto list = testing::RunProcess({VESICA_RECORDS_EXE, "--db", db_, "list"},
                                        {{"VESICA_RECORDS_DB", std::nullopt}}, 30, testing::kNobodyUid);
  const auto csv = testing::RunProcess({VESICA_RECORDS_EXE, "--db", db_, "export-csv", "--trainee", "ana"},
                                       {{"VESICA_RECORDS_DB", std::nullopt}}, 30, testing::kNobodyUid);
  fs::permissions(dir_.path(), fs::perms::owner_all, fs::perm_options::add);
  EXPECT_EQ(list.exit_code, 0) << list.err;
  EXPECT_EQ(list.out, "ana\nben\n");
  EXPECT_EQ(csv.exit_code, 0) << csv.err;
  EXPECT_EQ(testing::ReadCsv(csv.out).size(), 3u) << csv.out;
  std::stringstream after;
  after << std::ifstream(db_, std::ios::binary).rdbuf();
  EXPECT_EQ(after.str(), before);
  EXPECT_FALSE(fs::exists(db_ + "-wal"));
}

TEST_F(RecordsToolTest, UnreachableServerFailsWithMaskedPassword) {
  const auto run =
      Records({"--db", "host=/nonexistent-vesica-socket-dir user=ana password=s3cret dbname=vesica", "list"});
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.err, AllOf(HasSubstr("password=***"), HasSubstr(": connect: "), Not(HasSubstr("s3cret"))));
}

TEST_F(RecordsToolTest, UnwritableCsvFileFails) {
  const std::string file = (dir_.path() / "no-such-folder" / "ana.csv").string();
  const auto run = Records({"--db", db_, "export-csv", "--trainee", "ana", "-o", file});
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_THAT(run.err, HasSubstr("cannot write " + file));
}

TEST_F(RecordsToolTest, UsageErrorsExitNonZero) {
  EXPECT_NE(Records({"--db", db_}).exit_code, 0);                     // no subcommand
  EXPECT_NE(Records({"--db", db_, "export-csv"}).exit_code, 0);       // no --trainee
  EXPECT_NE(Records({"--db", db_, "list", "--bogus"}).exit_code, 0);  // unknown option
  EXPECT_EQ(Records({"--help"}).exit_code, 0);
}

TEST(RecordsToolPostgresTest, ListsFromAServer) {
  auto& server = testing::PostgresTestServer::Shared();
  ASSERT_TRUE(server.running()) << server.error();
  const std::string location = server.NewDatabase();
  OpenSessionStore(location)->Add(SampleRecord(0, "cy"));
  const auto run = Records({"--db", location, "list", "--trainee", "cy"});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, HasSubstr("2026-11-23T04:00:00Z"));
}

}  // namespace
}  // namespace vesica::app
