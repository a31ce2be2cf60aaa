#include "firmware_protocol/emulator/arm_plant_parameters.h"

namespace vesica::fp::emulator {

ArmPlantParameters ArmPlantParameters::Nominal() {
  ArmPlantParameters p;
  // Yaw and pitch: a 24 V precious-metal-brush DC motor (Kt 30.2 mNm/A, 2.5 ohm, 10.8 g cm^2)
  // on a 14:1 planetary gear; low friction keeps the arm back-drivable. Kt and ratio are the
  // node's parameter defaults (firmware_protocol/node/parameter_table.h).
  DcMotorParameters brushed;
  brushed.torque_constant_Nm_per_A = 0.0302;
  brushed.winding_resistance_Ohm = 2.5;
  brushed.rotor_inertia_kg_m2 = 1.08e-6;
  brushed.coulomb_friction_Nm = 0.3e-3;
  brushed.viscous_friction_Nm_s_per_rad = 1e-6;
  brushed.transmission_ratio = 14.0;
  brushed.supply_voltage_V = p.bus_V;
  brushed.current_loop_time_constant_s = 1e-4;
  p.motor[0] = brushed;
  p.motor[1] = brushed;
  // Insertion: flat BLDC (Kt 27.6 mNm/A) on a 10 mm capstan, no gear: 100 N per N m.
  DcMotorParameters bldc;
  bldc.torque_constant_Nm_per_A = 0.0276;
  bldc.winding_resistance_Ohm = 0.8;
  bldc.rotor_inertia_kg_m2 = 2.4e-6;
  bldc.coulomb_friction_Nm = 0.4e-3;
  bldc.viscous_friction_Nm_s_per_rad = 2e-6;
  bldc.transmission_ratio = 1.0 / 0.010;
  bldc.supply_voltage_V = p.bus_V;
  bldc.current_loop_time_constant_s = 1e-4;
  p.motor[2] = bldc;

  p.encoder[0] = {2048, 1.234};  // 512-line encoders, x4; index at arbitrary mounting angles
  p.encoder[1] = {2048, 4.321};
  p.encoder[2] = {4096, 0.777};
  return p;
}

}  // namespace vesica::fp::emulator
