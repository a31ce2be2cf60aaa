#include "device/stylus/stylus_recording.h"

#include <gtest/gtest.h>

namespace vesica::device {
namespace {

std::string Header() {
  return std::string(kStylusRecordingMagic) + "\n# a comment\n" + std::string(kStylusRecordingHeader) + "\n";
}

std::string ErrorOf(const std::string& text) {
  try {
    ParseStylusRecording(text, "biopsy.csv");
  } catch (const RecordingError& e) {
    return e.what();
  }
  return "";
}

TEST(StylusRecordingTest, FormatThenParseIsExact) {
  StylusRecording rec;
  for (int i = 0; i < 5; ++i) {
    StylusSample s;
    s.time_s = 0.1 * i + 1.0 / 3.0;
    s.state.p_BTip_B = {0.001 * i, -0.02 / 3.0, 1e-7};
    s.state.d_B = Eigen::Vector3d(0.2, -1.0, 0.1 * i).normalized();
    s.state.buttons = static_cast<std::uint32_t>(i % 4);
    rec.samples.push_back(s);
  }
  const StylusRecording back = ParseStylusRecording(FormatStylusRecording(rec), "mem");
  ASSERT_EQ(back.samples.size(), rec.samples.size());
  for (std::size_t i = 0; i < rec.samples.size(); ++i) {
    EXPECT_EQ(back.samples[i].time_s, rec.samples[i].time_s);
    EXPECT_EQ(back.samples[i].state.p_BTip_B, rec.samples[i].state.p_BTip_B);
    EXPECT_EQ(back.samples[i].state.d_B, rec.samples[i].state.d_B);
    EXPECT_EQ(back.samples[i].state.buttons, rec.samples[i].state.buttons);
  }
}

TEST(StylusRecordingTest, ParsesRowsAndNormalisesDirections) {
  const StylusRecording rec =
      ParseStylusRecording(Header() + "0,0.01,0,0,0,0,-2,1,0\r\n0.5,0.02,0,0,0,-3,0,0,1\n", "m");
  ASSERT_EQ(rec.samples.size(), 2u);
  EXPECT_EQ(rec.samples[0].state.d_B, Eigen::Vector3d(0, 0, -1));
  EXPECT_EQ(rec.samples[0].state.buttons, kStylusButton1);
  EXPECT_EQ(rec.samples[1].state.d_B, Eigen::Vector3d(0, -1, 0));
  EXPECT_EQ(rec.samples[1].state.buttons, kStylusButton2);
}

TEST(StylusRecordingTest, ErrorsNameFileLineAndWhat) {
  EXPECT_EQ(ErrorOf(Header() + "0,0,0,0,0,0,-1,0,0\n0.1,nan,0,0,0,0,-1,0,0\n"),
            "biopsy.csv:5 (t=0.1 s): stylus position (nan, 0, 0) m is not finite");
  EXPECT_EQ(ErrorOf(Header() + "0,0,0,0,0,0,-1,0,0\n0.1,0.5m,0,0,0,0,-1,0,0\n"),
            "biopsy.csv:5 (t=0 s): x_m is '0.5m', not a number");
  EXPECT_EQ(ErrorOf(Header() + "0,0,0,0,0,0,0,0,0\n"),
            "biopsy.csv:4 (t=0 s): stylus direction (0, 0, 0) has zero length (a direction needs a norm >= 1e-6)");
  EXPECT_EQ(ErrorOf(Header() + "0,0,0,0,0,0,-1,0,0\n0,0,0,0,0,0,-1,0,0\n"),
            "biopsy.csv:5 (t=0 s): time_s is not after the previous sample's");
  EXPECT_EQ(ErrorOf(Header() + "0,0,0,0,0,0,-1,2,0\n"), "biopsy.csv:4 (t=0 s): button1 is 2, must be 0 or 1");
  EXPECT_EQ(ErrorOf(Header() + "0,0,0\n"), "biopsy.csv:4: row has 3 fields, expected 9");
  EXPECT_EQ(ErrorOf(Header()), "biopsy.csv:3: has no samples");
  EXPECT_NE(ErrorOf("hello\n").find("biopsy.csv:1: not a stylus recording: line 1 is 'hello'"), std::string::npos);
}

// A recording of the other procedure is named as such, not as garbage.
TEST(StylusRecordingTest, ACholecystectomyRecordingIsTheWrongProcedure) {
  const std::string e = ErrorOf("# vesica input recording v1\ntime_s,left_yaw_rad\n");
  EXPECT_NE(e.find("biopsy.csv:1: this is a cholecystectomy input recording"), std::string::npos) << e;
  EXPECT_NE(e.find("not a stylus recording for the needle"), std::string::npos) << e;
}

TEST(StylusRecordingTest, UnreadableFileNamesThePath) {
  try {
    ReadStylusRecording("/nonexistent/stylus.csv");
    FAIL();
  } catch (const RecordingError& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/stylus.csv: cannot open the file");
    EXPECT_EQ(e.line(), 0);
  }
}

}  // namespace
}  // namespace vesica::device
