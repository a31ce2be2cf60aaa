#pragma once

namespace vesica::fp::emulator {

/// A current-driven DC motor (brushed or BLDC with commutation folded in) and its transmission
/// to one joint. Units are SI; effort and position on the joint side are rad / N m for a geared
/// rotary joint, m / N for the capstan-driven insertion.
struct DcMotorParameters {
  double torque_constant_Nm_per_A = 0.0;      ///< Kt, equal to back-EMF constant (V s/rad), > 0
  double winding_resistance_Ohm = 0.0;        ///< terminal resistance, > 0
  double rotor_inertia_kg_m2 = 0.0;           ///< rotor + gearbox input, >= 0
  double coulomb_friction_Nm = 0.0;           ///< motor side, >= 0
  double viscous_friction_Nm_s_per_rad = 0.0; ///< motor side, >= 0
  /// Joint effort per unit motor torque, > 0: gear ratio (1) or 1 / capstan radius (1/m).
  double transmission_ratio = 1.0;
  double supply_voltage_V = 24.0;             ///< H-bridge supply, > 0
  double current_loop_time_constant_s = 1e-4; ///< drive's current loop, first order, > 0
};

/// The motor's electrical state under its drive. The drive regulates the *measured* current to
/// the setpoint, so a current-sensor offset appears as an error in the real current (which is
/// why the firmware calibrates offsets). A setpoint of exactly zero switches the bridge off.
class DcMotor {
 public:
  explicit DcMotor(const DcMotorParameters& p) : p_(p) {}

  /// Advances the current by dt toward setpoint - sensor_offset (0 when the setpoint is 0: bridge
  /// off), bounded by what the supply can push against the back-EMF at omega_motor_rad_s.
  void Step(double dt_s, double setpoint_A, double sensor_offset_A, double omega_motor_rad_s);
  void Reset() { current_A_ = 0.0; }

  double current_A() const { return current_A_; }
  double motor_torque_Nm() const { return p_.torque_constant_Nm_per_A * current_A_; }
  /// Joint-side effort of the electromagnetic torque (before friction).
  double joint_effort() const { return motor_torque_Nm() * p_.transmission_ratio; }
  const DcMotorParameters& parameters() const { return p_; }

  /// Joint-side reflected quantities: inertia N^2 J, Coulomb N Tc, viscous N^2 b.
  double reflected_inertia() const { return p_.transmission_ratio * p_.transmission_ratio * p_.rotor_inertia_kg_m2; }
  double reflected_coulomb() const { return p_.transmission_ratio * p_.coulomb_friction_Nm; }
  double reflected_viscous() const {
    return p_.transmission_ratio * p_.transmission_ratio * p_.viscous_friction_Nm_s_per_rad;
  }

 private:
  DcMotorParameters p_;
  double current_A_ = 0.0;
};

}  // namespace vesica::fp::emulator
