#include "firmware_protocol/emulator/arm_plant.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vesica::fp::emulator {
namespace {

double Quantize(double v, double lsb) { return lsb > 0.0 ? std::round(v / lsb) * lsb : v; }

double WrapPi(double a) {
  const double two_pi = 2.0 * std::numbers::pi;
  a = std::fmod(a + std::numbers::pi, two_pi);
  if (a < 0.0) a += two_pi;
  return a - std::numbers::pi;
}

// Penalty force of a hard stop: spring-damper once the joint is past a limit, pushing back only.
double StopEffort(double q, double qd, double lo, double hi, double k, double b) {
  if (q < lo) return std::max(0.0, k * (lo - q) - b * qd);
  if (q > hi) return std::min(0.0, k * (hi - q) - b * qd);
  return 0.0;
}

// One semi-implicit Euler step of a joint with Karnopp stick-slip friction: a joint at rest
// stays at rest while the other efforts are within the Coulomb level; a joint whose velocity
// would cross zero this step stops there unless the efforts can break it loose.
double StepVelocity(double qd, double effort, double coulomb, double inertia, double dt) {
  if (qd == 0.0) {
    if (std::abs(effort) <= coulomb) return 0.0;
    return dt * (effort - std::copysign(coulomb, effort)) / inertia;
  }
  const double next = qd + dt * (effort - std::copysign(coulomb, qd)) / inertia;
  if ((next > 0.0) != (qd > 0.0) && std::abs(effort) <= coulomb) return 0.0;
  return next;
}

std::array<IncrementalEncoder, 3> MakeEncoders(const ArmPlantParameters& p, const Joint4& q0) {
  auto make = [&](int m) {
    return IncrementalEncoder(p.encoder[m], q0[JointOfMotor(m)] * p.motor[m].transmission_ratio);
  };
  return {make(0), make(1), make(2)};
}

}  // namespace

ArmPlant::ArmPlant(const ArmPlantParameters& params, const Joint4& q0)
    : p_(params),
      motors_{DcMotor(params.motor[0]), DcMotor(params.motor[1]), DcMotor(params.motor[2])},
      encoders_(MakeEncoders(params, q0)),
      q_(q0) {}

void ArmPlant::PowerUpAt(const Joint4& q) {
  motors_ = {DcMotor(p_.motor[0]), DcMotor(p_.motor[1]), DcMotor(p_.motor[2])};
  encoders_ = MakeEncoders(p_, q);
  setpoint_A_ = {};
  q_ = q;
  qd_ = Joint4{};
}

double ArmPlant::JointInertia(int joint) const {
  // Hand mass (while holding) reflected through the orthogonal Jacobian columns:
  // (d cos pitch)^2, d^2, 1.
  const double d = q_[3];
  const double cp = std::cos(q_[1]);
  const double m = script_.At(time_s_).holding ? p_.hand.mass_kg : 0.0;
  switch (joint) {
    case 0: return p_.yaw_link_inertia_kg_m2 + motors_[0].reflected_inertia() + m * d * d * cp * cp;
    case 1: return p_.pitch_link_inertia_kg_m2 + motors_[1].reflected_inertia() + m * d * d;
    case 2: return p_.roll_inertia_kg_m2;
    default: return p_.carriage_mass_kg + motors_[2].reflected_inertia() + m;
  }
}

void ArmPlant::Advance(double dt_s) {
  while (dt_s > 1e-12) {
    const double h = std::min(dt_s, p_.step_s);
    Step(h);
    dt_s -= h;
  }
}

void ArmPlant::Step(double dt) {
  const HandTarget target = script_.At(time_s_);
  const Vec3 f_hand = HandForceOnInstrument(p_.hand, target, TipPosition(q_), TipVelocity(q_, qd_));
  Joint4 effort = JointEffortsOfTipForce(q_, f_hand);
  if (target.holding)
    effort[2] = p_.hand.roll_stiffness_Nm_per_rad * (target.roll_rad - q_[2]) -
                p_.hand.roll_damping_Nm_s_per_rad * qd_[2];

  Joint4 coulomb{};
  for (int m = 0; m < 3; ++m) {
    const int j = JointOfMotor(m);
    motors_[m].Step(dt, setpoint_A_[m], p_.current_sensor_offset_A[m], qd_[j] * p_.motor[m].transmission_ratio);
    effort[j] += motors_[m].joint_effort() - motors_[m].reflected_viscous() * qd_[j];
    coulomb[j] = motors_[m].reflected_coulomb();
    effort[j] += load_.Effort(m, q_[j]);
  }
  effort[1] += p_.pitch_gravity_sin_Nm * std::sin(q_[1]) + p_.pitch_gravity_cos_Nm * std::cos(q_[1]);
  effort[2] -= p_.roll_viscous_Nm_s_per_rad * qd_[2];
  coulomb[2] = p_.roll_coulomb_Nm;

  for (int j = 0; j < 4; ++j) {
    const bool linear = j == 3;
    effort[j] += StopEffort(q_[j], qd_[j], p_.lower_limit[j], p_.upper_limit[j],
                            linear ? p_.linear_stop_stiffness_N_per_m : p_.rotary_stop_stiffness_Nm_per_rad,
                            linear ? p_.linear_stop_damping_N_s_per_m : p_.rotary_stop_damping_Nm_s_per_rad);
  }
  for (int j = 0; j < 4; ++j) {
    qd_[j] = StepVelocity(qd_[j], effort[j], coulomb[j], JointInertia(j), dt);
    q_[j] += qd_[j] * dt;
  }
  for (int m = 0; m < 3; ++m) encoders_[m].Update(q_[JointOfMotor(m)] * p_.motor[m].transmission_ratio);
  time_s_ += dt;
}

PlantSensors ArmPlant::ReadSensors() const {
  PlantSensors s;
  for (int m = 0; m < 3; ++m) {
    s.encoder_count[m] = encoders_[m].count();
    s.index_seen[m] = encoders_[m].index_seen();
    s.index_edges[m] = encoders_[m].index_edges();
    s.current_A[m] = motors_[m].current_A() + p_.current_sensor_offset_A[m];
  }
  s.roll_rad = WrapPi(Quantize(q_[2] + p_.roll_sensor_offset_rad, p_.roll_sensor_lsb_rad));
  const HandTarget target = script_.At(time_s_);
  const double jaw = std::clamp(target.jaw_rad, 0.0, p_.jaw_max_rad);
  s.jaw_rad = Quantize(jaw, p_.jaw_sensor_lsb_rad);
  const double travel = target.pedal_travel >= 0.0 ? std::min(target.pedal_travel, 1.0) : (target.pedal ? 1.0 : 0.0);
  s.pedal = target.pedal_travel >= 0.0 ? travel > 0.5 : target.pedal;
  s.roll_raw = RollRaw(q_[2] + p_.roll_sensor_offset_rad);
  s.jaw_raw = p_.hand_sensors.JawRaw(jaw);
  s.pedal_raw = p_.hand_sensors.PedalRaw(travel);
  s.bus_V = p_.bus_V;
  s.board_temperature_degC = p_.board_temperature_degC;
  return s;
}

std::array<double, 3> ArmPlant::motor_current_A() const {
  return {motors_[0].current_A(), motors_[1].current_A(), motors_[2].current_A()};
}

Vec3 ArmPlant::ForceOnHand() const {
  const Vec3 f = HandForceOnInstrument(p_.hand, script_.At(time_s_), TipPosition(q_), TipVelocity(q_, qd_));
  return {-f[0], -f[1], -f[2]};
}

Vec3 ArmPlant::ActuatorTipForce() const {
  const Joint4 tau{motors_[0].joint_effort(), motors_[1].joint_effort(), 0.0, motors_[2].joint_effort()};
  return TipForceOfJointEfforts(q_, tau);
}

}  // namespace vesica::fp::emulator
