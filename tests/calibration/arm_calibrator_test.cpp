// Acceptance of the calibration procedures (issue 32): 20 seeded random emulated arms over the
// virtual bus, each calibrated end to end; every recovered value against the arm's ground truth.
#include "device/calibration/arm_calibrator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "calibration_rig.h"
#include "firmware_protocol/node/parameter_table.h"

namespace vesica::device::calibration {
namespace {

using testing::CalibrationRig;

constexpr double kDeg = std::numbers::pi / 180.0;

class ArmCalibratorAcceptance : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(ArmCalibratorAcceptance, RecoversTheGroundTruth) {
  CalibrationRig rig(GetParam());
  const auto& t = rig.truth;
  CalibrationPlan plan;
  plan.date_s = 1'790'000'000;
  plan.tool_version = 0x000100;
  ArmCalibrator calibrator(*rig.link, plan);
  const CalibrationResult r = calibrator.Run();
  ASSERT_EQ(r.abort, AbortReason::kNone) << r.failed_step << ": " << r.message;
  ASSERT_TRUE(r.saved);
  const fp::ParameterStore& p = rig.emulator->node().parameters();
  for (int j = 0; j < 3; ++j) {
    const auto jj = static_cast<std::uint16_t>(j);
    const JointCalibration& c = r.joint[j];
    const double count = t.count(j);
    // Direction always right; offset and index within 2 encoder counts.
    EXPECT_EQ(c.direction, t.plant.encoder[j].direction) << "joint " << j;
    const double offset_error = c.position_offset - rig.TrueOffset(j, c.direction);
    EXPECT_LE(std::abs(offset_error), 2 * count) << "joint " << j << ": " << offset_error / count << " counts";
    const double index_error = c.index_position - t.reference_index(j);
    EXPECT_LE(std::abs(index_error), 2 * count) << "joint " << j << ": " << index_error / count << " counts";
    // Range within 0.5 degree (insertion: 0.5 mm).
    const double range_tol = j < 2 ? 0.5 * kDeg : 0.5e-3;
    EXPECT_NEAR(c.lower_stop, t.lower_stop(j), range_tol) << "joint " << j;
    EXPECT_NEAR(c.upper_stop, t.upper_stop(j), range_tol) << "joint " << j;
    // Friction in the node's torque units (its Kt): what a current really gives.
    const double kt = t.torque_constant_ratio(j, p.f32(fp::param::kTorqueConstant + jj));
    EXPECT_NEAR(c.coulomb, t.coulomb(j) / kt, 0.10 * t.coulomb(j) / kt) << "joint " << j;
    EXPECT_NEAR(c.viscous, t.viscous(j) / kt, 0.10 * t.viscous(j) / kt) << "joint " << j;
    EXPECT_NEAR(c.current_offset_A, t.plant.current_sensor_offset_A[j], 1e-4) << "joint " << j;
    // The node runs on what was found.
    EXPECT_EQ(static_cast<std::int32_t>(p.u32(fp::param::kEncoderDirection + jj)), c.direction);
    EXPECT_FLOAT_EQ(p.f32(fp::param::kPositionOffset + jj), static_cast<float>(c.position_offset));
    EXPECT_FLOAT_EQ(p.f32(fp::param::kCoulombFriction + jj), static_cast<float>(c.coulomb));
    std::printf(
        "seed %llu joint %d: offset %+.2f counts, index %+.2f counts, stops %+.3f %+.3f deg|mm, coulomb %+.1f %%, "
        "viscous %+.1f %%\n",
        static_cast<unsigned long long>(GetParam()), j, offset_error / count, index_error / count,
        (c.lower_stop - t.lower_stop(j)) / (j < 2 ? kDeg : 1e-3),
        (c.upper_stop - t.upper_stop(j)) / (j < 2 ? kDeg : 1e-3), 100 * (c.coulomb * kt / t.coulomb(j) - 1),
        100 * (c.viscous * kt / t.viscous(j) - 1));
  }
  // Gravity within 10 % of its amplitude over the pitch range.
  const double kt = t.torque_constant_ratio(1, p.f32(fp::param::kTorqueConstant + 1));
  const double gs = -t.plant.pitch_gravity_sin_Nm / kt, gc = -t.plant.pitch_gravity_cos_Nm / kt;
  const double amplitude = std::hypot(gs, gc);
  double worst = 0.0;
  for (double a = t.lower_stop(1); a <= t.upper_stop(1); a += 0.01)
    worst = std::max(worst, std::abs(r.gravity_sin * std::sin(a) + r.gravity_cos * std::cos(a) -
                                     (gs * std::sin(a) + gc * std::cos(a))));
  EXPECT_LE(worst, 0.10 * amplitude);
  std::printf("seed %llu gravity: worst %.1f %% of amplitude %.4f N m; %.1f s of bus time\n",
              static_cast<unsigned long long>(GetParam()), 100 * worst / amplitude, amplitude, rig.link->now_s());
  // Stored: a power cycle boots what was found, with the tool's date and version.
  rig.emulator->Reboot();
  const auto& booted = rig.emulator->node();
  EXPECT_EQ(booted.latched_fault(), fp::FaultCode::None);
  EXPECT_NE(booted.active_slot(), -1);
  EXPECT_EQ(booted.parameters().u32(fp::param::kCalibrationDate_s), plan.date_s);
  EXPECT_FLOAT_EQ(booted.parameters().f32(fp::param::kViscousFriction + 2), static_cast<float>(r.joint[2].viscous));
  EXPECT_FLOAT_EQ(booted.parameters().f32(fp::param::kGravitySin), static_cast<float>(r.gravity_sin));
}

INSTANTIATE_TEST_SUITE_P(TwentySeededArms, ArmCalibratorAcceptance, ::testing::Range<std::uint64_t>(1, 21));

}  // namespace
}  // namespace vesica::device::calibration

namespace vesica::device::calibration {
namespace {

TEST(ArmCalibratorTest, OneJointAloneLeavesTheOthersAsStored) {
  testing::CalibrationRig rig(11);
  CalibrationPlan plan;
  plan.joints = 0b001;  // yaw only
  const CalibrationResult r = ArmCalibrator(*rig.link, plan).Run();
  ASSERT_EQ(r.abort, AbortReason::kNone) << r.failed_step << ": " << r.message;
  const fp::ParameterStore& p = rig.emulator->node().parameters();
  EXPECT_EQ(r.joint[0].direction, rig.truth.plant.encoder[0].direction);
  EXPECT_NEAR(r.joint[0].lower_stop, rig.truth.lower_stop(0), 0.5 * kDeg);
  // Pitch and insertion: untouched defaults, no gravity measured.
  for (int j : {1, 2}) {
    const auto jj = static_cast<std::uint16_t>(j);
    EXPECT_EQ(p.f32(fp::param::kPositionOffset + jj), 0.0f);
    EXPECT_EQ(p.u32(fp::param::kEncoderDirection + jj), 1u);
    EXPECT_EQ(p.f32(fp::param::kCoulombFriction + jj), 0.0f);
    EXPECT_EQ(p.f32(fp::param::kJointMin + jj), fp::find_parameter(fp::param::kJointMin + jj)->default_value);
  }
  EXPECT_EQ(p.f32(fp::param::kGravitySin), 0.0f);
  EXPECT_TRUE(r.gravity_holds.empty());
}

}  // namespace
}  // namespace vesica::device::calibration

namespace vesica::device::calibration {
namespace {

TEST(ArmCalibratorTest, FrictionAloneOnACalibratedArmKeepsTheRest) {
  testing::CalibrationRig rig(12);
  ASSERT_EQ(ArmCalibrator(*rig.link, CalibrationPlan{}).Run().abort, AbortReason::kNone);
  const fp::ParameterStore before = rig.emulator->node().parameters();
  CalibrationPlan plan;
  plan.steps = kStepFriction;
  std::vector<std::string> ran;
  plan.progress = [&](const std::string& step, double f) {
    if (f == 0.0) ran.push_back(step);
  };
  const CalibrationResult r = ArmCalibrator(*rig.link, plan).Run();
  ASSERT_EQ(r.abort, AbortReason::kNone) << r.failed_step << ": " << r.message;
  EXPECT_EQ(ran, (std::vector<std::string>{"friction", "save"}));
  const fp::ParameterStore& after = rig.emulator->node().parameters();
  for (int j = 0; j < 3; ++j) {
    const auto jj = static_cast<std::uint16_t>(j);
    const double kt = rig.truth.torque_constant_ratio(j, after.f32(fp::param::kTorqueConstant + jj));
    EXPECT_NEAR(r.joint[j].coulomb, rig.truth.coulomb(j) / kt, 0.1 * rig.truth.coulomb(j) / kt);
    for (std::uint16_t base : {fp::param::kPositionOffset, fp::param::kEncoderDirection, fp::param::kIndexPosition,
                               fp::param::kCurrentOffset})
      EXPECT_EQ(after.u32(base + jj), before.u32(base + jj)) << "parameter 0x" << std::hex << base + jj;
    EXPECT_NEAR(after.f32(fp::param::kJointMin + jj), before.f32(fp::param::kJointMin + jj), 1e-6);
  }
  EXPECT_EQ(after.u32(fp::param::kGravitySin), before.u32(fp::param::kGravitySin));
  EXPECT_EQ(rig.emulator->node().slot_generation(rig.emulator->node().active_slot()), 2u);  // saved again
}

}  // namespace
}  // namespace vesica::device::calibration
