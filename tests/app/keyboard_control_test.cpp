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
  EXPECT_DOUBLE_EQ(poses[1].yaw_rad, step.angle_rad);
  ASSERT_TRUE(ApplyInstrumentKey('u', poses, max, pedal));
  EXPECT_DOUBLE_EQ(poses[1].insertion_m, 0.1 + step.insertion_m);
  ASSERT_TRUE(ApplyInstrumentKey('x', poses, max, pedal));
  EXPECT_DOUBLE_EQ(poses[0].jaw_angle_rad, step.jaw_open_rad);
  ASSERT_TRUE(ApplyInstrumentKey('x', poses, max, pedal));
  EXPECT_DOUBLE_EQ(poses[0].jaw_angle_rad, 0.0);
  ASSERT_TRUE(ApplyInstrumentKey('b', poses, max, pedal));  // the clip applier's or the scissors' jaw
  EXPECT_DOUBLE_EQ(poses[1].jaw_angle_rad, step.jaw_open_rad);
  EXPECT_DOUBLE_EQ(poses[0].jaw_angle_rad, 0.0);
  ASSERT_TRUE(ApplyInstrumentKey('B', poses, max, pedal));
  EXPECT_DOUBLE_EQ(poses[1].jaw_angle_rad, 0.0);
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

TEST(KeyboardControlTest, DragsTurnAndTheWheelInsertsLikeTheKeys) {
  std::vector<physics::InstrumentPose> poses(2), keyed(2);
  poses[1].insertion_m = keyed[1].insertion_m = 0.1;
  const std::vector<double> max{0.36, 0.12};
  const KeyboardStep step;
  bool pedal = false;
  // 5 px left and 5 px up on the grasper = 1 px / 0.002 rad each, as A and W would turn it.
  ASSERT_TRUE(ApplyInstrumentDrag(0, -5.0, -5.0, poses));
  for (int i = 0; i < 5; ++i) {
    ApplyInstrumentKey('a', keyed, max, pedal, KeyboardStep{.angle_rad = step.angle_rad_per_pixel});
    ApplyInstrumentKey('w', keyed, max, pedal, KeyboardStep{.angle_rad = step.angle_rad_per_pixel});
  }
  EXPECT_NEAR(poses[0].yaw_rad, -5 * step.angle_rad_per_pixel, 1e-15);
  EXPECT_NEAR(poses[0].yaw_rad, keyed[0].yaw_rad, 1e-15);
  EXPECT_NEAR(poses[0].pitch_rad, keyed[0].pitch_rad, 1e-15);
  EXPECT_EQ(poses[1].yaw_rad, 0.0);  // the other instrument stays
  // Right and down turn the other way; pitch stops at the limit.
  ASSERT_TRUE(ApplyInstrumentDrag(1, 10.0, 1e6, poses));
  EXPECT_NEAR(poses[1].yaw_rad, 10 * step.angle_rad_per_pixel, 1e-15);
  EXPECT_EQ(poses[1].pitch_rad, -step.max_pitch_rad);
  // Wheel: a notch away from the user inserts one step, within [0, max].
  ASSERT_TRUE(ApplyInstrumentWheel(1, 2.0, poses, max));
  EXPECT_NEAR(poses[1].insertion_m, 0.1 + 2 * step.insertion_m_per_wheel_notch, 1e-15);
  ASSERT_TRUE(ApplyInstrumentWheel(1, 100.0, poses, max));
  EXPECT_EQ(poses[1].insertion_m, 0.12);
  ASSERT_TRUE(ApplyInstrumentWheel(1, -1000.0, poses, max));
  EXPECT_EQ(poses[1].insertion_m, 0.0);
  EXPECT_FALSE(ApplyInstrumentDrag(2, 1.0, 1.0, poses));
  EXPECT_FALSE(ApplyInstrumentWheel(2, 1.0, poses, max));
}

}  // namespace
}  // namespace vesica::app
