#include "device/arm_actuation.h"

#include <cmath>

#include <gtest/gtest.h>

namespace vesica::device {
namespace {

const ArmJoints kPose{0.2, -0.1, 0.0, 0.12};

TEST(ArmActuationTest, NominalIsValidAndBrokenFieldIsNamed) {
  EXPECT_EQ(ArmActuation::Nominal().FirstInvalidField(), "");
  ArmActuation a = ArmActuation::Nominal();
  a.pitch.torque_constant_Nm_per_A = -1.0;
  EXPECT_EQ(a.FirstInvalidField(), "pitch.torque_constant_Nm_per_A");
  a = ArmActuation::Nominal();
  a.insertion.max_current_A = NAN;
  EXPECT_EQ(a.FirstInvalidField(), "insertion.max_current_A");
}

TEST(ArmActuationTest, CurrentsFollowJacobianTransposeGearAndTorqueConstant) {
  const ArmActuation a = ArmActuation::Nominal();
  const Eigen::Vector3d f(0.5, -0.3, 0.8);
  const MotorCurrentCommand cmd = TipForceToMotorCurrents(kPose, f, a);
  ASSERT_EQ(cmd.active_limit, ActuationLimit::kNone);
  const Eigen::Vector4d tau = JointEffortsFromTipForce(kPose, f);
  // Hand-derived: i = tau / (N Kt); insertion N = 1 / r.
  EXPECT_NEAR(cmd.current_A[0], tau[0] / (14.0 * 0.0302), 1e-12);
  EXPECT_NEAR(cmd.current_A[1], tau[1] / (14.0 * 0.0302), 1e-12);
  EXPECT_NEAR(cmd.current_A[2], tau[3] * 0.010 / 0.0276, 1e-12);
  EXPECT_EQ(cmd.scale, 1.0);
  EXPECT_TRUE(cmd.f_rendered_T.isApprox(f));
}

TEST(ArmActuationTest, SaturationKeepsDirectionAndNamesTheLimit) {
  ArmActuation a = ArmActuation::Nominal();
  a.yaw.max_current_A = 0.5;
  // A lateral force mostly along the yaw column at this pose needs a lot of yaw current.
  const Eigen::Vector3d f(5.0, 0.0, 0.0);
  const MotorCurrentCommand cmd = TipForceToMotorCurrents(kPose, f, a);
  EXPECT_EQ(cmd.active_limit, ActuationLimit::kYawCurrent);
  EXPECT_NEAR(std::abs(cmd.current_A[0]), 0.5, 1e-12);
  EXPECT_LT(cmd.scale, 1.0);
  EXPECT_LE(std::abs(cmd.current_A[1]), a.pitch.max_current_A);
  EXPECT_LE(std::abs(cmd.current_A[2]), a.insertion.max_current_A);
  // Same direction as asked.
  EXPECT_NEAR(cmd.f_rendered_T.normalized().dot(f.normalized()), 1.0, 1e-12);
}

TEST(ArmActuationTest, TipForceLimitCapsMagnitude) {
  const ArmActuation a = ArmActuation::Nominal();
  const Eigen::Vector3d f(0.0, 0.0, 3.0 * a.max_tip_force_N);
  const MotorCurrentCommand cmd = TipForceToMotorCurrents(kPose, f, a);
  EXPECT_NEAR(cmd.f_rendered_T.norm(), a.max_tip_force_N, 1e-12);
  EXPECT_EQ(cmd.active_limit, ActuationLimit::kTipForce);
  EXPECT_EQ(ToString(cmd.active_limit), "tip force");
}

TEST(ArmActuationTest, NonFiniteForceGivesZeroCurrent) {
  const MotorCurrentCommand cmd =
      TipForceToMotorCurrents(kPose, Eigen::Vector3d(NAN, 1.0, 0.0), ArmActuation::Nominal());
  EXPECT_EQ(cmd.current_A, Eigen::Vector3d::Zero());
  EXPECT_EQ(cmd.scale, 0.0);
}

}  // namespace
}  // namespace vesica::device
