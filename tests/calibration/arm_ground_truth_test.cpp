// The emulator's randomised arms: one seed, one arm; the ground truth shows in the plant
// (reversed encoders, stops where drawn, pitch imbalance), and the nominal arm is unchanged.
#include "firmware_protocol/emulator/arm_ground_truth.h"

#include <gtest/gtest.h>

#include <cmath>

#include "firmware_protocol/emulator/arm_plant.h"

namespace vesica::fp::emulator {
namespace {

TEST(ArmGroundTruthTest, OneSeedGivesOneArmAndSeedsDiffer) {
  const ArmGroundTruth a = RandomArm(7), b = RandomArm(7), c = RandomArm(8);
  EXPECT_EQ(a.plant.current_sensor_offset_A, b.plant.current_sensor_offset_A);
  EXPECT_EQ(a.power_up, b.power_up);
  EXPECT_EQ(a.plant.pitch_gravity_sin_Nm, b.plant.pitch_gravity_sin_Nm);
  EXPECT_NE(a.plant.current_sensor_offset_A, c.plant.current_sensor_offset_A);
}

TEST(ArmGroundTruthTest, DrawsStayInTheirDocumentedRanges) {
  int reversed = 0;
  for (std::uint64_t seed = 1; seed <= 200; ++seed) {
    const ArmGroundTruth t = RandomArm(seed);
    for (int m = 0; m < 3; ++m) {
      const bool rotary = m < 2;
      EXPECT_GE(t.coulomb(m), rotary ? 4e-3 : 0.2);
      EXPECT_LE(t.coulomb(m), rotary ? 12e-3 : 0.6);
      EXPECT_GE(t.viscous(m), rotary ? 2e-3 : 0.5);
      EXPECT_LE(t.viscous(m), rotary ? 6e-3 : 1.5);
      EXPECT_LE(std::abs(t.plant.current_sensor_offset_A[m]), 0.05);
      EXPECT_NEAR(t.lower_stop(m) + t.upper_stop(m), 2 * ArmGroundTruth::kDesignCentre[m], 1e-12);
      EXPECT_LE(std::abs(t.reference_index(m) - ArmGroundTruth::kDesignCentre[m]), t.index_spacing(m) / 2 + 1e-12);
      reversed += t.plant.encoder[m].direction < 0;
    }
    const double g = std::hypot(t.plant.pitch_gravity_sin_Nm, t.plant.pitch_gravity_cos_Nm);
    EXPECT_GE(g, 0.02 - 1e-12);
    EXPECT_LE(g, 0.05 + 1e-12);
  }
  EXPECT_GT(reversed, 200);  // about half of 600 encoders count backwards
  EXPECT_LT(reversed, 400);
}

TEST(ArmGroundTruthTest, PitchImbalancePullsAFreeJointDownToItsStop) {
  ArmGroundTruth t = RandomArm(3);
  t.plant.pitch_gravity_sin_Nm = 0.05;  // falls away from upright, toward the side it leans to
  t.plant.pitch_gravity_cos_Nm = 0.0;
  ArmPlant plant(t.plant, {0.0, 0.3, 0.0, 0.12});
  HandTarget let_go;
  let_go.holding = false;
  plant.SetHandScript(HandScript(let_go));
  plant.Advance(2.0);
  EXPECT_NEAR(plant.q()[1], t.upper_stop(1), 5e-4);  // resting on the upper stop
}

TEST(ArmGroundTruthTest, NominalArmIsBalancedWithForwardEncoders) {
  const ArmPlantParameters p = ArmPlantParameters::Nominal();
  EXPECT_EQ(p.pitch_gravity_sin_Nm, 0.0);
  EXPECT_EQ(p.pitch_gravity_cos_Nm, 0.0);
  for (int m = 0; m < 3; ++m) EXPECT_EQ(p.encoder[m].direction, 1);
}

}  // namespace
}  // namespace vesica::fp::emulator
