#pragma once

#include <cstdint>

#include "firmware_protocol/emulator/arm_plant.h"

namespace vesica::fp::emulator {

/// One randomised arm, as built and assembled: what a calibration has to find, drawn from a seed
/// so a failing arm can be rebuilt. Joint order for 3-vectors: yaw, pitch, insertion.
///
/// The arm's joint coordinates are defined by its mechanics: each joint's hard stops are machined
/// symmetric about the joint's design centre (kDesignCentre: 0 rad, 0 rad, 0.135 m), their span
/// varies from arm to arm. The encoder is incremental, so the board's reading is off by where the
/// arm happened to be at power-up (`power_up`, the board assumes park_position) and may count
/// backwards (`encoder[m].direction`); its index sits at a random mounting angle.
struct ArmGroundTruth {
  static constexpr double kDesignCentre[3] = {0.0, 0.0, 0.135};

  std::uint64_t seed = 0;
  ArmPlantParameters plant;  ///< what the emulator runs
  Joint4 power_up{};         ///< true joint positions at power-up (yaw, pitch, roll, insertion)

  /// Joint-side friction as the motor sees it (N m or N; N m s/rad or N s/m).
  double coulomb(int joint) const;
  double viscous(int joint) const;
  /// Reference index edge: the one nearest the joint's design centre, in joint units.
  double reference_index(int joint) const;
  /// Joint-side distance between index edges (one motor revolution), rad or m.
  double index_spacing(int joint) const;
  /// One encoder count on the joint side, rad or m.
  double count(int joint) const;
  double lower_stop(int joint) const;
  double upper_stop(int joint) const;
  /// Torque constant actual / nominal (the node's parameter): what a current really gives.
  double torque_constant_ratio(int joint, double nominal_Nm_per_A) const;
  /// The hand sensors (guided hand calibration): the roll encoder's reading minus the true roll,
  /// rad in (-pi, pi]; the jaw ADC at the handle fully closed and fully open; the pedal ADC
  /// released and pressed to its stop.
  double roll_offset() const { return plant.roll_sensor_offset_rad; }
  std::int32_t jaw_closed_raw() const { return plant.hand_sensors.JawRaw(0.0); }
  std::int32_t jaw_open_raw() const { return plant.hand_sensors.JawRaw(plant.jaw_max_rad); }
  std::int32_t pedal_up_raw() const { return plant.hand_sensors.PedalRaw(0.0); }
  std::int32_t pedal_down_raw() const { return plant.hand_sensors.PedalRaw(1.0); }
};

/// Seeded random arm: ranges and spreads documented in the .cpp next to each draw.
ArmGroundTruth RandomArm(std::uint64_t seed);

/// Where an arm powers up after someone moved it by hand while it was off: yaw and pitch
/// distance_rad away from `from`, insertion distance_rad / 10 m (0.07 m for 0.7), each way drawn
/// from the seed; a move that would come within 0.05 rad (5 mm) of a stop goes the other way.
/// Roll stays. distance_rad >= 0, at most 0.9.
Joint4 MovedWhileOff(const ArmPlantParameters& plant, const Joint4& from, double distance_rad, std::uint64_t seed);

}  // namespace vesica::fp::emulator
