// docs/calibration/sample is what the tool writes: the committed report (JSON and HTML) equals a
// fresh one made with the command docs/calibration.md gives. When the procedures change, make it
// again with that command and commit the folder's files.
#include <gtest/gtest.h>

#include "tool_process.h"

namespace vesica::app::calibrate {
namespace {

TEST(CalibrateSample, TheCommittedSampleReportIsWhatTheToolWrites) {
  const std::string dir = testing::FreshDir("sample");
  const auto run = testing::RunTool(
      {"--emulated", "7", "--dir", dir, "--yes", "--quiet", "--json", "--date", "1790000000", "calibrate", "1"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string session = run.json()["session_dir"].get<std::string>();
  const std::string sample = std::string(VESICA_SOURCE_DIR) + "/docs/calibration/sample/";
  for (const char* f : {"arm1-calibrate.json", "arm1-calibrate.html", "arm1-stored.vcal"})
    EXPECT_EQ(testing::ReadBytes(session + "/" + f), testing::ReadBytes(sample + f))
        << f << " differs from a fresh one (" << session << "): regenerate docs/calibration/sample";
}

}  // namespace
}  // namespace vesica::app::calibrate
