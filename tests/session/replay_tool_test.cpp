// vesica-replay as a user runs it: metrics printed for a good recording, a broken one rejected
// with the line and time where it breaks (exit 2).

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

struct Result {
  int status = -1;
  std::string output;
};

Result RunTool(const std::string& args) {
  Result r;
  const std::string command = std::string(VESICA_REPLAY_EXE) + " " + args + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), pipe) != nullptr) r.output += buf.data();
  const int status = pclose(pipe);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::filesystem::path WriteTemp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("vesica_replay_tool_test_" + name);
  std::ofstream(path) << text;
  return path;
}

std::string FirstLines(int n) {
  std::ifstream in(std::filesystem::path(VESICA_SOURCE_DIR) / "data/recordings/dissection.csv");
  std::string line, out;
  for (int i = 0; i < n && std::getline(in, line); ++i) out += line + "\n";
  return out;
}

TEST(ReplayToolTest, PrintsTheMetricsOfARecording) {
  // The first 0.5 s of the committed recording (3 comment/header lines + 100 rows).
  const auto path = WriteTemp("head.csv", FirstLines(103));
  const Result r = RunTool(path.string());
  EXPECT_EQ(r.status, 0) << r.output;
  for (const char* field :
       {"session time          0.500 s (100 steps)", "gallbladder free      no", "slips", "liver damage",
        "gallbladder damage", "tissue removed", "max force", "state digest", "step wall time        median "})
    EXPECT_NE(r.output.find(field), std::string::npos) << field << "\n" << r.output;
}

TEST(ReplayToolTest, TruncatedRecordingIsRejectedWithLineAndTime) {
  std::string text = FirstLines(53);
  text += text.substr(text.rfind('\n', text.size() - 2) + 1, 40);  // half a row, no line end
  const auto path = WriteTemp("truncated.csv", text);
  const Result r = RunTool(path.string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("recording rejected"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(path.string() + ":54"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(t="), std::string::npos) << r.output;
}

TEST(ReplayToolTest, MissingRecordingIsNamed) {
  const Result r = RunTool("/nonexistent/recording.csv");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("/nonexistent/recording.csv"), std::string::npos) << r.output;
}

}  // namespace
