#include "device/stylus/stylus_recorder.h"

#include <gtest/gtest.h>

#include <limits>

namespace vesica::device {
namespace {

TEST(StylusRecorderTest, RecordsAndRoundTripsThroughTheFormat) {
  StylusRecorder recorder;
  StylusState s;
  s.d_B = {0.0, -2.0, 0.0};
  recorder.Append(0.0, s);
  s.p_BTip_B = {0.001, 0.0, 0.0};
  s.buttons = kStylusButton1;
  recorder.Append(0.001, s);
  ASSERT_EQ(recorder.recording().samples.size(), 2u);
  EXPECT_EQ(recorder.recording().samples[0].state.d_B, Eigen::Vector3d(0, -1, 0));
  const StylusRecording back = ParseStylusRecording(FormatStylusRecording(recorder.recording()), "mem");
  EXPECT_EQ(back.samples[1].state.p_BTip_B, Eigen::Vector3d(0.001, 0.0, 0.0));
  EXPECT_EQ(back.samples[1].state.buttons, kStylusButton1);
}

TEST(StylusRecorderTest, BadSamplesAreRefusedRecordingUnchanged) {
  StylusRecorder recorder;
  recorder.Append(1.0, StylusState{});
  StylusState nan_pose;
  nan_pose.p_BTip_B.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(recorder.Append(2.0, nan_pose), std::invalid_argument);
  StylusState no_direction;
  no_direction.d_B.setZero();
  EXPECT_THROW(recorder.Append(2.0, no_direction), std::invalid_argument);
  try {
    recorder.Append(1.0, StylusState{});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sample 1: time_s is not after the previous sample's"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(recorder.recording().samples.size(), 1u);
}

}  // namespace
}  // namespace vesica::device
