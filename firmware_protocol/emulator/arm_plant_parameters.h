#pragma once

#include <array>

#include "firmware_protocol/emulator/dc_motor.h"
#include "firmware_protocol/emulator/hand_model.h"
#include "firmware_protocol/emulator/hand_sensors.h"
#include "firmware_protocol/emulator/incremental_encoder.h"

namespace vesica::fp::emulator {

/// Everything physical about one emulated arm (gallbladder paper §2.5.4): yaw and pitch
/// direct-drive joints on brushed geared DC motors, insertion by a wire drive from an ungeared
/// BLDC, roll measured by an absolute sensor, a jaw handle sensor and a foot pedal.
/// Joint order for 3-vectors: yaw, pitch, insertion; for 4-vectors: yaw, pitch, roll, insertion.
/// The arm is assumed gravity balanced (counterweights), as such haptic arms are built.
struct ArmPlantParameters {
  std::array<DcMotorParameters, 3> motor;
  std::array<EncoderParameters, 3> encoder;
  std::array<double, 3> current_sensor_offset_A{};  ///< added to every current reading

  double yaw_link_inertia_kg_m2 = 3e-3;     ///< gimbal about the yaw axis, > 0
  double pitch_link_inertia_kg_m2 = 2e-3;   ///< about the pitch axis, > 0
  double roll_inertia_kg_m2 = 2e-5;         ///< instrument about its shaft, > 0
  double carriage_mass_kg = 0.12;           ///< insertion carriage + instrument, > 0
  double roll_viscous_Nm_s_per_rad = 2e-4;  ///< roll bearing
  double roll_coulomb_Nm = 2e-4;

  Joint4 lower_limit{-1.05, -1.05, -3.0, 0.02};  ///< hard stops: rad, rad, rad, m
  Joint4 upper_limit{1.05, 1.05, 3.0, 0.25};
  double rotary_stop_stiffness_Nm_per_rad = 200.0;
  double rotary_stop_damping_Nm_s_per_rad = 1.0;
  double linear_stop_stiffness_N_per_m = 2e4;
  double linear_stop_damping_N_s_per_m = 60.0;

  /// Residual imbalance of the pitch link: gravity's torque on pitch is
  /// sin * sin(pitch) + cos * cos(pitch), N m (zero: balanced, as the nominal arm).
  double pitch_gravity_sin_Nm = 0.0;
  double pitch_gravity_cos_Nm = 0.0;

  double roll_sensor_offset_rad = 0.0;      ///< absolute magnetic sensor mounting offset
  double roll_sensor_lsb_rad = 3.835e-4;    ///< 14 bits per turn
  double jaw_sensor_lsb_rad = 1e-3;         ///< Hall handle sensor resolution
  double jaw_max_rad = 0.6;                 ///< handle fully open
  HandSensorModel hand_sensors;             ///< raw jaw and pedal ADCs (protocol 1.2 readout)

  double bus_V = 24.0;
  double board_temperature_degC = 30.0;
  double step_s = 1e-4;                     ///< plant integration step (10 kHz), > 0
  HandParameters hand;
  /// The arm left the factory calibrated: ArmEmulator programs its flash with the calibration
  /// that matches these parameters (factory_calibration.h), so the node boots it. False: a board
  /// nobody calibrated (RandomArm's arms, or an explicitly uncalibrated nominal arm).
  bool factory_calibrated = true;

  /// The nominal arm; device::ArmActuation::Nominal() carries the same motor figures.
  static ArmPlantParameters Nominal();
};

}  // namespace vesica::fp::emulator
