#include "firmware_protocol/emulator/dc_motor.h"

#include <algorithm>
#include <cmath>

namespace vesica::fp::emulator {

void DcMotor::Step(double dt_s, double setpoint_A, double sensor_offset_A, double omega_motor_rad_s) {
  // Zero setpoint is "free" (NodeHardware::apply_currents): the bridge is off and the current
  // dies out whatever the sensor reads. Otherwise the loop servoes the reading onto the setpoint.
  const double target = setpoint_A == 0.0 ? 0.0 : setpoint_A - sensor_offset_A;
  // Exact first-order step, so any dt is stable.
  const double alpha = 1.0 - std::exp(-dt_s / p_.current_loop_time_constant_s);
  double next = current_A_ + alpha * (target - current_A_);
  // Voltage headroom: |R i + Ke w| <= V.
  const double back_emf_V = p_.torque_constant_Nm_per_A * omega_motor_rad_s;
  const double hi = (p_.supply_voltage_V - back_emf_V) / p_.winding_resistance_Ohm;
  const double lo = (-p_.supply_voltage_V - back_emf_V) / p_.winding_resistance_Ohm;
  current_A_ = std::clamp(next, lo, hi);
}

}  // namespace vesica::fp::emulator
