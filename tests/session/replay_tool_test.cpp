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

// The header lines of the committed recording with its scenario line replaced by `scenario_line`.
std::string WithScenarioLine(std::string text, const std::string& scenario_line) {
  const std::string line = "# scenario: Laparoscopic cholecystectomy\n";
  const auto at = text.find(line);
  if (at == std::string::npos) return "scenario line not found";
  return text.replace(at, line.size(), scenario_line);
}

TEST(ReplayToolTest, SpanBeyondTheDoublesStepsIsRefused) {
  // A last row at 1e308 s once gave floor(1e308 / h) = inf steps, cast to a long: 0 steps, exit 0.
  std::string text = FirstLines(4);
  text += "1e308" + text.substr(text.rfind('\n', text.size() - 2) + 2);
  const auto path = WriteTemp("far.csv", text);
  const Result r = RunTool(path.string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find(path.string() + ": the recording spans 1e+308 s, more than a replay runs (at most 43200 s"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("session time"), std::string::npos) << r.output;
}

TEST(ReplayToolTest, RecordingOfAnotherScenarioIsRefused) {
  const auto path = WriteTemp("other_scenario.csv", WithScenarioLine(FirstLines(13), "# scenario: Appendectomy\n"));
  const Result r = RunTool(path.string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find(path.string() + ": recorded in scenario 'Appendectomy', but "), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("is 'Laparoscopic cholecystectomy'"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("session time"), std::string::npos) << r.output;
}

TEST(ReplayToolTest, AnyScenarioReplaysAnotherScenariosRecordingWithProgressLines) {
  // Rows 0 to 0.045 s: 10 steps of 5 ms, a line at each tenth on request.
  const auto path = WriteTemp("other_scenario_ok.csv", WithScenarioLine(FirstLines(13), "# scenario: Appendectomy\n"));
  const Result r = RunTool("--any-scenario --progress lines " + path.string());
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("recorded in scenario 'Appendectomy', replayed in 'Laparoscopic cholecystectomy'"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("replay progress:  10% (0.005 of 0.050 s)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("replay progress: 100% (0.050 of 0.050 s)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("session time          0.050 s (10 steps)"), std::string::npos) << r.output;
}

TEST(ReplayToolTest, ShortReplayOffATerminalPrintsNoProgress) {
  const auto path = WriteTemp("short.csv", FirstLines(13));
  const Result r = RunTool(path.string());
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("progress"), std::string::npos) << r.output;
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
