#include "firmware_protocol/emulator/dc_motor.h"

#include <cmath>

#include <gtest/gtest.h>

namespace vesica::fp::emulator {
namespace {

DcMotorParameters Motor() {
  DcMotorParameters p;
  p.torque_constant_Nm_per_A = 0.03;
  p.winding_resistance_Ohm = 2.0;
  p.transmission_ratio = 14.0;
  p.supply_voltage_V = 24.0;
  p.current_loop_time_constant_s = 1e-4;
  return p;
}

TEST(DcMotorTest, FirstOrderCurrentLoopReachesSetpoint) {
  DcMotor m(Motor());
  m.Step(1e-4, 1.0, 0.0, 0.0);  // one time constant
  EXPECT_NEAR(m.current_A(), 1.0 - std::exp(-1.0), 1e-12);
  for (int i = 0; i < 100; ++i) m.Step(1e-4, 1.0, 0.0, 0.0);
  EXPECT_NEAR(m.current_A(), 1.0, 1e-9);
  EXPECT_NEAR(m.joint_effort(), 1.0 * 0.03 * 14.0, 1e-9);
}

TEST(DcMotorTest, SensorOffsetShiftsTheRealCurrent) {
  // The drive servoes the measured current (real + offset) onto the setpoint.
  DcMotor m(Motor());
  for (int i = 0; i < 200; ++i) m.Step(1e-4, 1.0, 0.1, 0.0);
  EXPECT_NEAR(m.current_A(), 0.9, 1e-9);
}

TEST(DcMotorTest, ZeroSetpointSwitchesBridgeOff) {
  DcMotor m(Motor());
  for (int i = 0; i < 200; ++i) m.Step(1e-4, 0.0, 0.1, 0.0);
  EXPECT_EQ(m.current_A(), 0.0);  // not -offset: nothing drives the winding
}

TEST(DcMotorTest, BackEmfLimitsCurrentAtSpeed) {
  DcMotor m(Motor());
  const double omega = 700.0;  // Ke w = 21 V leaves 3 V across 2 ohm: at most 1.5 A
  for (int i = 0; i < 200; ++i) m.Step(1e-4, 5.0, 0.0, omega);
  EXPECT_NEAR(m.current_A(), (24.0 - 0.03 * omega) / 2.0, 1e-12);
}

TEST(DcMotorTest, ReflectedQuantitiesScaleWithRatio) {
  DcMotorParameters p = Motor();
  p.rotor_inertia_kg_m2 = 1e-6;
  p.coulomb_friction_Nm = 2e-4;
  p.viscous_friction_Nm_s_per_rad = 1e-6;
  const DcMotor m(p);
  EXPECT_NEAR(m.reflected_inertia(), 196e-6, 1e-15);
  EXPECT_NEAR(m.reflected_coulomb(), 2.8e-3, 1e-15);
  EXPECT_NEAR(m.reflected_viscous(), 196e-6, 1e-15);
}

}  // namespace
}  // namespace vesica::fp::emulator
