// vesica-trainer --replay as a user runs it: a recording that cannot be replayed ends the program
// with the reason on stderr and a non-zero status, before any window opens (it once opened the
// window and carried on with the keyboard). Run under Xvfb so that a window could open.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

struct Result {
  int status = -1;
  std::string output;
};

Result RunTrainer(const std::string& args) {
  Result r;
  const std::string command = std::string(XVFB_RUN) + " -a -s '-screen 0 640x480x24' " + VESICA_TRAINER_EXE +
                              " --records none --width 640 --height 360 --quit-after-ms 1500 " + args + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), pipe) != nullptr) r.output += buf.data();
  const int status = pclose(pipe);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

TEST(TrainerReplayArgumentTest, MissingRecordingEndsWithTheReasonBeforeAWindowOpens) {
  const Result r = RunTrainer("--replay /nonexistent/missing.csv");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--replay: recording rejected: /nonexistent/missing.csv: cannot open input recording"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("loop rates"), std::string::npos) << r.output;  // logged after a window closes
}

TEST(TrainerReplayArgumentTest, TruncatedRecordingNamesItsLine) {
  const auto path = std::filesystem::temp_directory_path() / "vesica_trainer_replay_argument_test.csv";
  std::ofstream(path) << "# vesica input recording v1\ntime_s,left_yaw_rad\n";
  const Result r = RunTrainer("--replay " + path.string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--replay: recording rejected: " + path.string() + ":2: header"), std::string::npos)
      << r.output;
  std::filesystem::remove(path);
}

}  // namespace
