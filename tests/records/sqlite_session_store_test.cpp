// What only the SQLite backend promises: a WAL-mode file, created with its folders, and clear
// errors for locations that cannot hold a database.

#include "app/records/sqlite_session_store.h"

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
