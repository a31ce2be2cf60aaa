#include "firmware_protocol/emulator/arm_plant.h"

#include <cmath>

#include <gtest/gtest.h>

namespace vesica::fp::emulator {
namespace {

HandTarget LetGo() {
  HandTarget t;
  t.holding = false;
  return t;
}

double Norm(const Vec3& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

TEST(ArmPlantTest, FreeInsertionAcceleratesAsForceOverMass) {
  ArmPlantParameters p = ArmPlantParameters::Nominal();
  ArmPlant plant(p, {0.0, 0.0, 0.0, 0.10});
  plant.SetHandScript(HandScript(LetGo()));
  plant.SetCurrentSetpoints({0.0, 0.0, 1.0});
  plant.Advance(0.002);  // let the current loop settle (20 time constants)
  const double d0 = plant.q()[3], v0 = plant.qd()[3];
  const double T = 0.01;
  plant.Advance(T);
  const DcMotorParameters& m = p.motor[2];
  const double force = m.torque_constant_Nm_per_A * 1.0 * m.transmission_ratio - m.coulomb_friction_Nm * m.transmission_ratio;
  const double mass = p.carriage_mass_kg + m.rotor_inertia_kg_m2 * m.transmission_ratio * m.transmission_ratio;
  // Viscous drag is tiny over 10 ms; compare to the constant-acceleration solution within 1%.
  const double expected = v0 * T + 0.5 * force / mass * T * T;
  EXPECT_NEAR(plant.q()[3] - d0, expected, 0.01 * expected);
}

TEST(ArmPlantTest, CurrentBelowCoulombLevelDoesNotMove) {
  ArmPlantParameters p = ArmPlantParameters::Nominal();
  ArmPlant plant(p, {0.1, 0.1, 0.0, 0.10});
  plant.SetHandScript(HandScript(LetGo()));
  // Yaw Coulomb at the motor is 0.3 mN m; 5 mA gives 0.15 mN m.
  plant.SetCurrentSetpoints({0.005, 0.0, 0.0});
  plant.Advance(0.5);
  EXPECT_EQ(plant.q()[0], 0.1);
  EXPECT_EQ(plant.qd()[0], 0.0);
}

TEST(ArmPlantTest, HeldArmSettlesWhereHandBalancesMotors) {
  ArmPlantParameters p = ArmPlantParameters::Nominal();
  ArmPlant plant(p, {0.2, -0.1, 0.0, 0.12});
  HandTarget hold;
  hold.p_T = TipPosition({0.2, -0.1, 0.0, 0.12});
  plant.SetHandScript(HandScript(hold));
  plant.SetCurrentSetpoints({0.3, -0.2, 0.5});
  plant.Advance(1.5);
  const Vec3 f_hand = plant.ForceOnHand();
  const Vec3 f_act = plant.ActuatorTipForce();
  // At rest the hand carries what the motors push, up to the Coulomb friction reflected to the
  // tip: yaw/pitch 14 * 0.3 mN m over ~0.12 m, insertion 100 * 0.4 mN m: below 0.1 N together.
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(f_hand[k], f_act[k], 0.1);
  EXPECT_GT(Norm(f_act), 1.0);
  EXPECT_LT(std::abs(plant.qd()[0]) + std::abs(plant.qd()[1]) + std::abs(plant.qd()[3]), 1e-3);
}

TEST(ArmPlantTest, HardStopHoldsJointAtItsLimit) {
  ArmPlantParameters p = ArmPlantParameters::Nominal();
  ArmPlant plant(p, {0.0, 0.0, 0.0, 0.20});
  plant.SetHandScript(HandScript(LetGo()));
  plant.SetCurrentSetpoints({0.0, 0.0, 2.0});  // 5.5 N outward along the shaft
  plant.Advance(1.0);
  const double push = 2.0 * p.motor[2].torque_constant_Nm_per_A * p.motor[2].transmission_ratio -
                      p.motor[2].coulomb_friction_Nm * p.motor[2].transmission_ratio;
  // Penalty stop: rests past the limit by push / k (within the friction band).
  EXPECT_NEAR(plant.q()[3], p.upper_limit[3] + push / p.linear_stop_stiffness_N_per_m, 1e-5);
}

TEST(ArmPlantTest, SensorsShowOffsetsAndEncoderCounts) {
  ArmPlantParameters p = ArmPlantParameters::Nominal();
  p.current_sensor_offset_A = {0.05, -0.02, 0.0};
  p.roll_sensor_offset_rad = 0.3;
  ArmPlant plant(p, {0.0, 0.0, 0.5, 0.10});
  HandTarget hold;
  hold.p_T = TipPosition({0.05, 0.0, 0.0, 0.10});  // pulls yaw to 0.05 rad
  hold.roll_rad = 0.5;
  hold.jaw_rad = 0.25;
  hold.pedal = true;
  plant.SetHandScript(HandScript(hold));
  plant.Advance(1.0);
  const PlantSensors s = plant.ReadSensors();
  // Zero setpoint: bridge off, no real current; the sensor reads its offset.
  EXPECT_NEAR(s.current_A[0], 0.05, 1e-9);
  EXPECT_NEAR(plant.motor_current_A()[0], 0.0, 1e-9);
  // Driven: the loop servoes the reading, so the real current is off by the offset.
  plant.SetCurrentSetpoints({0.2, 0.0, 0.0});
  plant.Advance(0.002);
  EXPECT_NEAR(plant.ReadSensors().current_A[0], 0.2, 1e-6);
  EXPECT_NEAR(plant.motor_current_A()[0], 0.15, 1e-6);
  plant.SetCurrentSetpoints({0.0, 0.0, 0.0});
  EXPECT_NEAR(s.roll_rad, 0.8, p.roll_sensor_lsb_rad);
  EXPECT_NEAR(s.jaw_rad, 0.25, p.jaw_sensor_lsb_rad);
  EXPECT_TRUE(s.pedal);
  const double rad_per_count = 2.0 * M_PI / p.encoder[0].counts_per_rev / p.motor[0].transmission_ratio;
  EXPECT_NEAR(s.encoder_count[0] * rad_per_count, plant.q()[0], rad_per_count);
  EXPECT_GT(plant.q()[0], 0.04);
}

TEST(HandScriptTest, InterpolatesPositionsAndHoldsDiscreteFields) {
  HandScript script;
  HandTarget a, b;
  a.p_T = {0.0, 0.0, 0.1};
  b.p_T = {0.02, 0.0, 0.1};
  b.pedal = true;
  b.jaw_rad = 0.4;
  ASSERT_TRUE(script.Add(1.0, a));
  ASSERT_TRUE(script.Add(2.0, b));
  EXPECT_FALSE(script.Add(1.5, a));  // out of order is refused
  const HandTarget mid = script.At(1.25);
  EXPECT_NEAR(mid.p_T[0], 0.005, 1e-15);
  EXPECT_NEAR(mid.jaw_rad, 0.1, 1e-15);
  EXPECT_FALSE(mid.pedal);
  EXPECT_TRUE(script.At(5.0).pedal);
  EXPECT_EQ(script.At(0.0).p_T[0], 0.0);
}

}  // namespace
}  // namespace vesica::fp::emulator
