// Each session's input gets its own file: two sessions started in the same second used to share
// one name and overwrite each other's input; a trainee id with a '/' pointed into a folder that
// does not exist.

#include "app/session/session_recording_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

namespace vesica::app {
namespace {

class SessionRecordingFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("vesica_recording_file_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(SessionRecordingFileTest, SessionsInTheSameSecondGetTheirOwnFiles) {
  const auto first = CreateSessionRecordingFile(dir_ / "recordings", "ana", 1795406400);
  const auto second = CreateSessionRecordingFile(dir_ / "recordings", "ana", 1795406400);
  const auto third = CreateSessionRecordingFile(dir_ / "recordings", "ana", 1795406400);
  EXPECT_EQ(first, dir_ / "recordings" / "ana-session-1795406400.csv");
  EXPECT_EQ(second, dir_ / "recordings" / "ana-session-1795406400-2.csv");
  EXPECT_EQ(third, dir_ / "recordings" / "ana-session-1795406400-3.csv");
  EXPECT_TRUE(std::filesystem::is_regular_file(second));
}

TEST_F(SessionRecordingFileTest, TraineeIdBecomesOneSafeFileName) {
  EXPECT_EQ(SafeFileNamePart("ward 3/ana"), "ward_3_ana");
  EXPECT_EQ(SafeFileNamePart("../../etc"), ".._.._etc");
  EXPECT_EQ(SafeFileNamePart(".."), "trainee");
  EXPECT_EQ(SafeFileNamePart(""), "trainee");
  EXPECT_EQ(CreateSessionRecordingFile(dir_, "ward 3/ana", 7), dir_ / "ward_3_ana-session-7.csv");
}

TEST_F(SessionRecordingFileTest, FolderThatCannotBeCreatedIsNamed) {
  std::filesystem::create_directories(dir_);
  std::ofstream(dir_ / "file") << "x";
  try {
    CreateSessionRecordingFile(dir_ / "file" / "recordings", "ana", 7);
    FAIL() << "created a recording under a file";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find((dir_ / "file" / "recordings").string() + ": cannot be created"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace vesica::app
