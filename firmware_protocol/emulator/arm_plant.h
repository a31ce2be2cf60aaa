#pragma once

#include <array>
#include <cstdint>

#include "firmware_protocol/emulator/arm_geometry.h"
#include "firmware_protocol/emulator/arm_plant_parameters.h"
#include "firmware_protocol/emulator/dc_motor.h"
#include "firmware_protocol/emulator/hand_model.h"
#include "firmware_protocol/emulator/incremental_encoder.h"
#include "firmware_protocol/emulator/reference_load.h"

namespace vesica::fp::emulator {

/// What the board's sensors read, raw as the firmware would see them.
struct PlantSensors {
  std::array<std::int32_t, 3> encoder_count{};   ///< since power-up
  std::array<bool, 3> index_seen{};              ///< index edge passed since power-up
  std::array<std::uint32_t, 3> index_edges{};    ///< index edges crossed since power-up
  std::array<double, 3> current_A{};            ///< true current + sensor offset
  double roll_rad = 0.0;                         ///< absolute sensor, wrapped to (-pi, pi]
  double jaw_rad = 0.0;                          ///< handle sensor, quantized
  bool pedal = false;
  std::int32_t roll_raw = 0;   ///< absolute roll encoder, 0..16383 a turn
  std::int32_t jaw_raw = 0;    ///< jaw handle ADC, 0..4095
  std::int32_t pedal_raw = 0;  ///< pedal ADC, 0..4095
  double bus_V = 0.0;
  double board_temperature_degC = 0.0;
};

/// The mechanics and electrics of one arm held by a scripted hand. Joint dynamics are
/// decoupled per joint (the actuated Jacobian columns are orthogonal, so a point mass at the tip
/// gives a diagonal joint-space inertia; velocity-product terms are neglected at hand speeds),
/// with Karnopp stick-slip Coulomb friction, viscous friction and penalty hard stops.
class ArmPlant {
 public:
  /// q0: the true joint positions at power-up (yaw, pitch, roll, insertion); encoders count
  /// from there.
  ArmPlant(const ArmPlantParameters& params, const Joint4& q0);

  /// Current loop setpoints from the firmware, A (yaw, pitch, insertion). Held until changed.
  void SetCurrentSetpoints(const std::array<double, 3>& amps) { setpoint_A_ = amps; }
  void SetHandScript(const HandScript& script) { script_ = script; }
  /// The torque-constant check's fixture clamped on (or, with attached false, taken off).
  void SetReferenceLoad(const ReferenceLoad& load) { load_ = load; }

  /// Power off, the arm moved to q by hand, power on: the joints at rest at q, the motors without
  /// current, the encoders counting afresh from there (their index edges stay where they are).
  void PowerUpAt(const Joint4& q);

  /// Advances the plant by dt_s in steps of at most params.step_s.
  void Advance(double dt_s);

  PlantSensors ReadSensors() const;

  // Ground truth, for tests and logs.
  double time_s() const { return time_s_; }
  const Joint4& q() const { return q_; }
  const Joint4& qd() const { return qd_; }
  std::array<double, 3> motor_current_A() const;
  /// Force the instrument pushes into the hand (tip-equivalent, T frame, N).
  Vec3 ForceOnHand() const;
  /// Tip force the motors' electromagnetic torques alone would produce (no friction), N.
  Vec3 ActuatorTipForce() const;
  HandTarget CurrentHandTarget() const { return script_.At(time_s_); }
  const ArmPlantParameters& parameters() const { return p_; }

 private:
  void Step(double dt_s);
  double JointInertia(int joint) const;

  ArmPlantParameters p_;
  std::array<DcMotor, 3> motors_;
  std::array<IncrementalEncoder, 3> encoders_;
  std::array<double, 3> setpoint_A_{};
  HandScript script_;
  ReferenceLoad load_;
  Joint4 q_;
  Joint4 qd_{};
  double time_s_ = 0.0;
};

/// Joint index (in Joint4) driven by motor m (yaw, pitch, insertion).
constexpr int JointOfMotor(int m) { return m == 2 ? 3 : m; }

}  // namespace vesica::fp::emulator
