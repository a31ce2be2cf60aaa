// The host's use of an arm's calibration: the compensation efforts (analytic), the feed-forward
// currents inside the actuation limits, and the factory calibration of the emulated arms.
#include "device/arm_calibration.h"

#include <gtest/gtest.h>

#include <cmath>

#include "device/arm_actuation.h"
#include "firmware_protocol/emulator/arm_ground_truth.h"
#include "firmware_protocol/emulator/factory_calibration.h"

namespace vesica::device {
namespace {

namespace emu = fp::emulator;

ArmCalibration Sample() {
  ArmCalibration c;
  c.coulomb = {0.01, 0.008, 0.4};
  c.viscous = {0.004, 0.003, 1.2};
  c.gravity_sin = -0.03;
  c.gravity_cos = 0.01;
  c.effort_per_amp = {0.0302 * 14, 0.0302 * 14, 0.0276 * 100};
  return c;
}

TEST(ArmCalibrationTest, CompensationCancelsFrictionAndHoldsPitch) {
  const ArmCalibration c = Sample();
  const ArmJoints q{0.3, 0.4, 0.0, 0.12};
  // Moving faster than the fade speed: full Coulomb against the motion plus viscous.
  const Eigen::Vector4d qd(0.2, -0.3, 5.0, -0.02);
  const Eigen::Vector3d tau = c.CompensationEffort(q, qd);
  EXPECT_NEAR(tau[0], 0.01 + 0.004 * 0.2, 1e-15);
  EXPECT_NEAR(tau[1], -0.008 - 0.003 * 0.3 + (-0.03 * std::sin(0.4) + 0.01 * std::cos(0.4)), 1e-15);
  EXPECT_NEAR(tau[2], -0.4 - 1.2 * 0.02, 1e-15);  // roll's velocity plays no part
  const Eigen::Vector3d amps = c.CompensationCurrent(q, qd);
  for (int j = 0; j < 3; ++j) EXPECT_NEAR(amps[j], tau[j] / c.effort_per_amp[j], 1e-15);
}

TEST(ArmCalibrationTest, CoulombFadesOutBelowItsSpeedAndGravityStays) {
  const ArmCalibration c = Sample();
  const ArmJoints q{0.0, -0.5, 0.0, 0.1};
  const Eigen::Vector3d at_rest = c.CompensationEffort(q, Eigen::Vector4d::Zero());
  EXPECT_EQ(at_rest[0], 0.0);
  EXPECT_EQ(at_rest[2], 0.0);
  EXPECT_NEAR(at_rest[1], -0.03 * std::sin(-0.5) + 0.01 * std::cos(-0.5), 1e-15);
  // Half the fade speed: half the Coulomb level (plus viscous).
  const Eigen::Vector3d slow = c.CompensationEffort(q, Eigen::Vector4d(0.025, 0.0, 0.0, 0.0025));
  EXPECT_NEAR(slow[0], 0.5 * 0.01 + 0.004 * 0.025, 1e-15);
  EXPECT_NEAR(slow[2], 0.5 * 0.4 + 1.2 * 0.0025, 1e-15);
}

TEST(ArmCalibrationTest, FeedForwardIsAddedAndTheSumStaysWithinEveryCurrentLimit) {
  const ArmActuation a = ArmActuation::Nominal();
  const ArmJoints q{0.2, -0.1, 0.0, 0.12};
  const Eigen::Vector3d ff(0.1, -0.2, 0.3);
  const Eigen::Vector3d f(0.5, -0.3, 0.8);
  const MotorCurrentCommand plain = TipForceToMotorCurrents(q, f, a);
  const MotorCurrentCommand cmd = TipForceToMotorCurrents(q, f, a, ff);
  EXPECT_EQ(cmd.scale, 1.0);
  EXPECT_TRUE(cmd.current_A.isApprox(plain.current_A + ff, 1e-12));
  EXPECT_TRUE(cmd.feedforward_A.isApprox(ff, 0.0));
  EXPECT_TRUE(cmd.joint_effort.isApprox(plain.joint_effort, 0.0));  // the tip force's efforts
  // A force beyond the insertion current (the tip force limit lifted): the tip force gets the
  // current the feed-forward leaves.
  ArmActuation strong = a;
  strong.max_tip_force_N = 1e6;
  const MotorCurrentCommand big = TipForceToMotorCurrents(q, Eigen::Vector3d(0.0, 0.0, 1000.0), strong, ff);
  EXPECT_EQ(big.active_limit, ActuationLimit::kInsertionCurrent);
  EXPECT_NEAR(std::abs(big.current_A[2]), a.insertion.max_current_A, 1e-12);
  EXPECT_NEAR(big.current_A[2] - ff[2], a.insertion.max_current_A - ff[2], 1e-12);
  EXPECT_LE(std::abs(big.current_A[0]), a.yaw.max_current_A);
  EXPECT_LE(std::abs(big.current_A[1]), a.pitch.max_current_A);
  // A non-finite feed-forward gives no current at all.
  EXPECT_EQ(TipForceToMotorCurrents(q, f, a, Eigen::Vector3d(NAN, 0, 0)).current_A, Eigen::Vector3d::Zero());
}

TEST(FactoryCalibrationTest, MatchesTheGroundTruthOfTheArmInTheNodesUnits) {
  // A random arm as the factory would have calibrated it.
  emu::ArmGroundTruth t = emu::RandomArm(4);
  const fp::JointArray park{0.0f, 0.0f, 0.135f};
  const fp::ParameterStore s = emu::FactoryCalibration(t.plant, t.power_up, park);
  for (int j = 0; j < 3; ++j) {
    const auto jj = static_cast<std::uint16_t>(j);
    const double kt = t.torque_constant_ratio(j, s.f32(fp::param::kTorqueConstant + jj));
    EXPECT_EQ(static_cast<std::int32_t>(s.u32(fp::param::kEncoderDirection + jj)), t.plant.encoder[j].direction);
    const double expected_offset = t.power_up[emu::JointOfMotor(j)] -
                                   t.plant.encoder[j].direction * static_cast<double>(park[j]) + 0.5 * t.count(j);
    EXPECT_NEAR(s.f32(fp::param::kPositionOffset + jj), expected_offset, 1e-6);
    EXPECT_NEAR(s.f32(fp::param::kCurrentOffset + jj), t.plant.current_sensor_offset_A[j], 1e-7);
    EXPECT_NEAR(s.f32(fp::param::kCoulombFriction + jj), t.coulomb(j) / kt, 1e-6 * t.coulomb(j));
    EXPECT_NEAR(s.f32(fp::param::kViscousFriction + jj), t.viscous(j) / kt, 1e-6 * t.viscous(j));
    EXPECT_NEAR(s.f32(fp::param::kIndexPosition + jj), t.reference_index(j), 1e-6);
  }
  const double kt = t.torque_constant_ratio(1, s.f32(fp::param::kTorqueConstant + 1));
  EXPECT_NEAR(s.f32(fp::param::kGravitySin), -t.plant.pitch_gravity_sin_Nm / kt, 1e-7);
  EXPECT_NEAR(s.f32(fp::param::kGravityCos), -t.plant.pitch_gravity_cos_Nm / kt, 1e-7);
}

}  // namespace
}  // namespace vesica::device
