#include "device/stylus/replay_stylus.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace vesica::device {
namespace {

StylusRecording TwoSamples() {
  StylusRecording rec;
  StylusSample a;
  a.time_s = 1.0;
  a.state.p_BTip_B = {0.0, 0.0, 0.0};
  a.state.d_B = {1.0, 0.0, 0.0};
  a.state.buttons = kStylusButton1;
  StylusSample b;
  b.time_s = 2.0;
  b.state.p_BTip_B = {0.02, -0.04, 0.0};
  b.state.d_B = {0.0, 1.0, 0.0};
  rec.samples = {a, b};
  return rec;
}

TEST(ReplayStylusTest, InterpolatesPositionAndDirectionHoldsButtons) {
  ReplayStylus replay(TwoSamples());
  ASSERT_EQ(replay.Open(), DeviceStatus::kOk);
  ASSERT_EQ(replay.Seek(1.5), DeviceStatus::kOk);
  const StylusState s = replay.GetStylusState();
  EXPECT_LT((s.p_BTip_B - Eigen::Vector3d(0.01, -0.02, 0.0)).norm(), 1e-15);
  EXPECT_LT((s.d_B - Eigen::Vector3d(1.0, 1.0, 0.0).normalized()).norm(), 1e-15);
  EXPECT_EQ(s.buttons, kStylusButton1);
  EXPECT_EQ(replay.SampleAt(2.0).buttons, 0u);
}

TEST(ReplayStylusTest, ClampsBeforeAndAfterAndIsAPureFunctionOfTime) {
  ReplayStylus replay(TwoSamples());
  EXPECT_EQ(replay.SampleAt(-5.0).p_BTip_B, Eigen::Vector3d::Zero());
  EXPECT_EQ(replay.SampleAt(9.0).p_BTip_B, Eigen::Vector3d(0.02, -0.04, 0.0));
  const StylusState forward = replay.SampleAt(1.25);
  replay.Seek(1.9);
  replay.Seek(1.1);
  EXPECT_EQ(replay.SampleAt(1.25).p_BTip_B, forward.p_BTip_B);
  EXPECT_TRUE(replay.finished(2.1));
  EXPECT_FALSE(replay.finished(2.0));
}

TEST(ReplayStylusTest, NaNTimeIsRefusedStateUnchanged) {
  ReplayStylus replay(TwoSamples());
  replay.Seek(1.5);
  const StylusState before = replay.GetStylusState();
  EXPECT_EQ(replay.Seek(std::numeric_limits<double>::quiet_NaN()), DeviceStatus::kInvalidArgument);
  EXPECT_EQ(replay.GetStylusState().p_BTip_B, before.p_BTip_B);
}

TEST(ReplayStylusTest, BadRecordingsAreRefused) {
  EXPECT_THROW(ReplayStylus(StylusRecording{}), std::invalid_argument);
  StylusRecording rec = TwoSamples();
  rec.samples[1].state.d_B.setZero();
  try {
    ReplayStylus r(rec);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sample 1: stylus direction (0, 0, 0) has zero length"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace vesica::device
