#include "app/trainer/keyboard_control.h"

#include <gtest/gtest.h>

namespace vesica::app {
namespace {

TEST(KeyboardControlTest, KeysMoveTheRightInstrumentByOneStep) {
  std::vector<physics::InstrumentPose> poses(2);
  poses[0].insertion_m = poses[1].insertion_m = 0.1;
  const std::vector<double> max{0.36, 0.36};
  bool pedal = false;
  const KeyboardStep step;
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(ApplyInstrumentKey('W', poses, max, pedal));  // case-insensitive
  EXPECT_DOUBLE_EQ(poses[0].pitch_rad, 5 * step.angle_rad);
  EXPECT_DOUBLE_EQ(poses[1].pitch_rad, 0.0);
  ASSERT_TRUE(ApplyInstrumentKey('l', poses, max, pedal));
  EXPECT_DOUBLE_EQ(poses[1].yaw_rad, -step.angle_rad);
  ASSERT_TRUE(ApplyInstrumentKey('u', poses, max, pedal));
  EXPECT_DOUBLE_EQ(poses[1].insertion_m, 0.1 + step.insertion_m);
  ASSERT_TRUE(ApplyInstrumentKey('x', poses, max, pedal));
  EXPECT_DOUBLE_EQ(poses[0].jaw_angle_rad, step.jaw_open_rad);
  ASSERT_TRUE(ApplyInstrumentKey('x', poses, max, pedal));
  EXPECT_DOUBLE_EQ(poses[0].jaw_angle_rad, 0.0);
  ASSERT_TRUE(ApplyInstrumentKey('m', poses, max, pedal));
  EXPECT_TRUE(pedal);
  EXPECT_FALSE(ApplyInstrumentKey('p', poses, max, pedal));
}

TEST(KeyboardControlTest, InsertionAndPitchStayInRange) {
  std::vector<physics::InstrumentPose> poses(2);
  const std::vector<double> max{0.01, 0.36};
  bool pedal = false;
  const KeyboardStep step;
  for (int i = 0; i < 100; ++i) ApplyInstrumentKey('q', poses, max, pedal);
  EXPECT_DOUBLE_EQ(poses[0].insertion_m, 0.01);
  for (int i = 0; i < 100; ++i) ApplyInstrumentKey('e', poses, max, pedal);
  EXPECT_DOUBLE_EQ(poses[0].insertion_m, 0.0);
  for (int i = 0; i < 1000; ++i) ApplyInstrumentKey('i', poses, max, pedal);
  EXPECT_DOUBLE_EQ(poses[1].pitch_rad, step.max_pitch_rad);
}

}  // namespace
}  // namespace vesica::app
