#include "device/stylus/stylus_state.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <limits>

#include "device/stylus/stylus_capabilities.h"
#include "device/stylus/stylus_force.h"

namespace vesica::device {
namespace {

TEST(StylusStateTest, AFiniteNonZeroDirectionIsFine) {
  StylusState s;
  s.d_B = {0.0, 3.0, 4.0};
  EXPECT_EQ(StylusStateProblem(s), std::nullopt);
  EXPECT_NEAR(NormalizedStylus(s).d_B.y(), 0.6, 1e-15);
  EXPECT_NEAR(NormalizedStylus(s).d_B.z(), 0.8, 1e-15);
}

TEST(StylusStateTest, NaNPositionIsNamed) {
  StylusState s;
  s.p_BTip_B.y() = std::numeric_limits<double>::quiet_NaN();
  const auto problem = StylusStateProblem(s);
  ASSERT_TRUE(problem);
  EXPECT_NE(problem->find("stylus position"), std::string::npos) << *problem;
  EXPECT_NE(problem->find("not finite"), std::string::npos) << *problem;
}

TEST(StylusStateTest, ZeroLengthDirectionIsNamed) {
  StylusState s;
  s.d_B = {0.0, 0.0, 1e-9};
  const auto problem = StylusStateProblem(s);
  ASSERT_TRUE(problem);
  EXPECT_NE(problem->find("zero length"), std::string::npos) << *problem;
}

TEST(StylusStateTest, UnknownButtonBitsAreRefused) {
  StylusState s;
  s.buttons = 0x4;
  const auto problem = StylusStateProblem(s);
  ASSERT_TRUE(problem);
  EXPECT_NE(problem->find("0x4"), std::string::npos) << *problem;
}

TEST(StylusStateTest, UnitDirectionSurvivesNormalisationBitForBit) {
  StylusState s;
  s.d_B = Eigen::Vector3d(0.3, -0.5, 0.7).normalized();
  EXPECT_EQ(NormalizedStylus(s).d_B, s.d_B);
}

TEST(StylusStateTest, ToolStateZAxisIsTheStylusDirection) {
  StylusState s;
  s.p_BTip_B = {0.01, 0.02, -0.03};
  s.d_B = Eigen::Vector3d(1.0, -2.0, 0.5).normalized();
  s.buttons = kStylusButton2;
  const ToolState tool = ToolStateFromStylus(s);
  EXPECT_LT((tool.R_BTip.col(2) - s.d_B).norm(), 1e-12);
  EXPECT_LT((tool.R_BTip * tool.R_BTip.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  EXPECT_NEAR(tool.R_BTip.determinant(), 1.0, 1e-12);
  EXPECT_EQ(tool.p_BTip_B, s.p_BTip_B);
  EXPECT_EQ(tool.buttons, kStylusButton2);
}

TEST(StylusCapabilitiesTest, OmniAsSpecified) {
  const StylusCapabilities c = PhantomOmniCapabilities();
  EXPECT_EQ(c.device.position_dof, 3);
  EXPECT_EQ(c.device.rotation_dof, 3);
  EXPECT_EQ(c.device.force_dof, 3);
  EXPECT_EQ(c.device.torque_dof, 0);
  EXPECT_EQ(c.device.button_count, 2);
  EXPECT_DOUBLE_EQ(c.device.max_force_N, 3.3);
  EXPECT_DOUBLE_EQ(c.device.servo_rate_hz, 1000.0);
  EXPECT_EQ(c.workspace_box_m, Eigen::Vector3d(0.160, 0.120, 0.070));
  EXPECT_TRUE(InsideWorkspace(c, {0.08, -0.06, 0.035}));
  EXPECT_FALSE(InsideWorkspace(c, {0.0, 0.0, 0.0351}));
  EXPECT_EQ(ClampToWorkspace(c, {1.0, -1.0, 0.01}), Eigen::Vector3d(0.08, -0.06, 0.01));
}

TEST(StylusForceTest, SaturationKeepsDirection) {
  const Eigen::Vector3d f = SaturateForce({3.0, 4.0, 0.0}, 3.3);
  EXPECT_NEAR(f.norm(), 3.3, 1e-12);
  EXPECT_NEAR(f.x() / f.y(), 0.75, 1e-12);
  EXPECT_EQ(SaturateForce({1.0, 0.0, -1.0}, 3.3), Eigen::Vector3d(1.0, 0.0, -1.0));
  EXPECT_TRUE(ForceProblem({0.0, std::numeric_limits<double>::infinity(), 0.0}));
  EXPECT_FALSE(ForceProblem({0.0, 1.0, 0.0}));
}

}  // namespace
}  // namespace vesica::device
