#include "device/stylus/keyboard_stylus.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace vesica::device {
namespace {

TEST(KeyboardStylusTest, KeysMoveTheTipByOneStep) {
  KeyboardStylus stylus;
  ASSERT_EQ(stylus.Open(), DeviceStatus::kOk);
  EXPECT_TRUE(stylus.ApplyKey('d'));
  EXPECT_TRUE(stylus.ApplyKey('R'));  // case-insensitive
  EXPECT_TRUE(stylus.ApplyKey('w'));
  EXPECT_LT((stylus.GetStylusState().p_BTip_B - Eigen::Vector3d(0.001, 0.001, -0.001)).norm(), 1e-15);
  EXPECT_FALSE(stylus.ApplyKey('x'));
}

TEST(KeyboardStylusTest, AdvanceMovesAlongTheStylusAndWithdrawComesBack) {
  StylusState start;
  start.d_B = Eigen::Vector3d(0.0, -1.0, -1.0).normalized();
  KeyboardStylus stylus(start);
  for (int i = 0; i < 10; ++i) stylus.ApplyKey('q');
  const Eigen::Vector3d p = stylus.GetStylusState().p_BTip_B;
  EXPECT_NEAR(p.dot(start.d_B.normalized()), 0.010, 1e-12);
  EXPECT_NEAR((p - p.dot(start.d_B.normalized()) * start.d_B.normalized()).norm(), 0.0, 1e-12);
  for (int i = 0; i < 10; ++i) stylus.ApplyKey('e');
  EXPECT_LT(stylus.GetStylusState().p_BTip_B.norm(), 1e-12);
}

TEST(KeyboardStylusTest, TurningKeepsTheDirectionUnitAndTurnsByTheStep) {
  KeyboardStylus stylus;  // D = -z
  stylus.ApplyKey('j');
  const Eigen::Vector3d d = stylus.GetStylusState().d_B;
  EXPECT_NEAR(d.norm(), 1.0, 1e-15);
  EXPECT_NEAR(std::acos(-d.z()), 2.0 * std::numbers::pi / 180.0, 1e-9);
  EXPECT_LT(d.x(), 0.0);  // j turns the tip to the left
  stylus.ApplyKey('l');
  EXPECT_LT((stylus.GetStylusState().d_B - Eigen::Vector3d(0, 0, -1)).norm(), 1e-12);
  stylus.ApplyKey('i');
  EXPECT_GT(stylus.GetStylusState().d_B.y(), 0.0);  // i raises the tip
}

TEST(KeyboardStylusTest, MouseAndWheel) {
  KeyboardStylus stylus;
  stylus.ApplyDrag(100.0, -50.0);  // right and up on the screen
  EXPECT_LT((stylus.GetStylusState().p_BTip_B - Eigen::Vector3d(0.010, 0.005, 0.0)).norm(), 1e-12);
  stylus.ApplyWheel(3.0);
  EXPECT_NEAR(stylus.GetStylusState().p_BTip_B.z(), -0.003, 1e-12);
}

TEST(KeyboardStylusTest, StaysInTheOmniWorkspace) {
  KeyboardStylus stylus;
  for (int i = 0; i < 200; ++i) stylus.ApplyKey('a');
  EXPECT_DOUBLE_EQ(stylus.GetStylusState().p_BTip_B.x(), -0.080);
  for (int i = 0; i < 200; ++i) stylus.ApplyKey('s');
  EXPECT_DOUBLE_EQ(stylus.GetStylusState().p_BTip_B.z(), 0.035);
}

TEST(KeyboardStylusTest, Buttons) {
  KeyboardStylus stylus;
  EXPECT_TRUE(stylus.SetButton(1, true));
  EXPECT_TRUE(stylus.SetButton(2, true));
  EXPECT_EQ(stylus.GetStylusState().buttons, kStylusButton1 | kStylusButton2);
  EXPECT_TRUE(stylus.SetButton(1, false));
  EXPECT_EQ(stylus.GetStylusState().buttons, kStylusButton2);
  EXPECT_FALSE(stylus.SetButton(3, true));
  EXPECT_EQ(stylus.GetStylusState().buttons, kStylusButton2);
}

TEST(KeyboardStylusTest, BadPoseIsRefusedAndTheStylusStays) {
  KeyboardStylus stylus;
  stylus.ApplyKey('d');
  const StylusState before = stylus.GetStylusState();
  StylusState nan_pose;
  nan_pose.p_BTip_B.z() = std::numeric_limits<double>::quiet_NaN();
  std::string error;
  EXPECT_FALSE(stylus.SetPose(nan_pose, &error));
  EXPECT_NE(error.find("keyboard stylus: stylus position"), std::string::npos) << error;
  StylusState no_direction;
  no_direction.d_B.setZero();
  EXPECT_FALSE(stylus.SetPose(no_direction, &error));
  EXPECT_NE(error.find("zero length"), std::string::npos) << error;
  EXPECT_EQ(stylus.GetStylusState().p_BTip_B, before.p_BTip_B);
  EXPECT_EQ(stylus.GetStylusState().d_B, before.d_B);
  EXPECT_THROW(KeyboardStylus{no_direction}, std::invalid_argument);
}

TEST(KeyboardStylusTest, ForceIsKeptSaturatedOnlyWhileOpen) {
  KeyboardStylus stylus;
  EXPECT_EQ(stylus.SetTipForce({1.0, 0.0, 0.0}), DeviceStatus::kNotOpen);
  ASSERT_EQ(stylus.Open(), DeviceStatus::kOk);
  EXPECT_EQ(stylus.SetTipForce({0.0, 6.6, 0.0}), DeviceStatus::kOk);
  EXPECT_EQ(stylus.RenderedForce(), Eigen::Vector3d(0.0, 3.3, 0.0));
  EXPECT_EQ(stylus.SetTipForce({std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0}), DeviceStatus::kInvalidArgument);
  EXPECT_EQ(stylus.RenderedForce(), Eigen::Vector3d(0.0, 3.3, 0.0));
  stylus.Close();
  EXPECT_EQ(stylus.RenderedForce(), Eigen::Vector3d::Zero());
}

}  // namespace
}  // namespace vesica::device
