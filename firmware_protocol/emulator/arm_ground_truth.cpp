#include "firmware_protocol/emulator/arm_ground_truth.h"

#include <cmath>
#include <numbers>
#include <random>

namespace vesica::fp::emulator {
namespace {

// Uniform draw written out (std::uniform_real_distribution differs between standard libraries,
// and a seed must give the same arm everywhere).
double Uniform(std::mt19937_64& rng, double lo, double hi) {
  const double u = static_cast<double>(rng() >> 11) * (1.0 / 9007199254740992.0);  // [0, 1)
  return lo + (hi - lo) * u;
}

}  // namespace

double ArmGroundTruth::coulomb(int j) const {
  return plant.motor[j].transmission_ratio * plant.motor[j].coulomb_friction_Nm;
}

double ArmGroundTruth::viscous(int j) const {
  const double n = plant.motor[j].transmission_ratio;
  return n * n * plant.motor[j].viscous_friction_Nm_s_per_rad;
}

double ArmGroundTruth::index_spacing(int j) const { return 2.0 * std::numbers::pi / plant.motor[j].transmission_ratio; }

double ArmGroundTruth::count(int j) const {
  return 2.0 * std::numbers::pi / plant.encoder[j].counts_per_rev / plant.motor[j].transmission_ratio;
}

double ArmGroundTruth::reference_index(int j) const {
  // Index edges sit at motor angle index_angle + 2 pi k, i.e. joint position (index + 2 pi k) / N.
  const double n = plant.motor[j].transmission_ratio;
  const double spacing = index_spacing(j);
  const double first = plant.encoder[j].index_angle_rad / n;
  const double k = std::round((kDesignCentre[j] - first) / spacing);
  return first + k * spacing;
}

double ArmGroundTruth::lower_stop(int j) const { return plant.lower_limit[JointOfMotor(j)]; }
double ArmGroundTruth::upper_stop(int j) const { return plant.upper_limit[JointOfMotor(j)]; }

double ArmGroundTruth::torque_constant_ratio(int j, double nominal_Nm_per_A) const {
  return plant.motor[j].torque_constant_Nm_per_A / nominal_Nm_per_A;
}

ArmGroundTruth RandomArm(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  ArmGroundTruth t;
  t.seed = seed;
  ArmPlantParameters& p = t.plant;
  p = ArmPlantParameters::Nominal();
  p.factory_calibrated = false;  // as built: what a calibration has to find is not stored yet
  for (int m = 0; m < 3; ++m) {
    DcMotorParameters& motor = p.motor[m];
    const double n = motor.transmission_ratio;
    // Torque constant within +-5 % of the datasheet (the node's parameter).
    motor.torque_constant_Nm_per_A *= Uniform(rng, 0.95, 1.05);
    // Friction at the joint: gears and seals of a back-drivable haptic arm.
    const bool rotary = m < 2;
    const double coulomb = rotary ? Uniform(rng, 4e-3, 12e-3) : Uniform(rng, 0.2, 0.6);  // N m or N
    const double viscous = rotary ? Uniform(rng, 2e-3, 6e-3) : Uniform(rng, 0.5, 1.5);   // N m s/rad or N s/m
    motor.coulomb_friction_Nm = coulomb / n;
    motor.viscous_friction_Nm_s_per_rad = viscous / (n * n);
    p.current_sensor_offset_A[m] = Uniform(rng, -0.05, 0.05);
    p.encoder[m].direction = rng() % 2 == 0 ? 1 : -1;
    p.encoder[m].index_angle_rad = Uniform(rng, 0.0, 2.0 * std::numbers::pi);
    // Stops symmetric about the design centre; span +-5 % (rotary) or +-5 mm (insertion).
    const int joint = JointOfMotor(m);
    const double half = rotary ? Uniform(rng, 1.0, 1.1) : Uniform(rng, 0.110, 0.120);
    p.lower_limit[joint] = ArmGroundTruth::kDesignCentre[m] - half;
    p.upper_limit[joint] = ArmGroundTruth::kDesignCentre[m] + half;
  }
  // Machined stops are stiff.
  p.rotary_stop_stiffness_Nm_per_rad = 2000.0;
  p.rotary_stop_damping_Nm_s_per_rad = 3.0;
  p.linear_stop_stiffness_N_per_m = 2e5;
  p.linear_stop_damping_N_s_per_m = 200.0;
  // Pitch imbalance: amplitude 20..50 mN m, its angle within +-0.3 rad of upright.
  const double g = Uniform(rng, 0.02, 0.05);
  const double phase = Uniform(rng, -0.3, 0.3);
  p.pitch_gravity_sin_Nm = g * std::cos(phase);
  p.pitch_gravity_cos_Nm = -g * std::sin(phase);
  // Where the arm was at power-up (the board assumes it parked).
  t.power_up = {Uniform(rng, -0.5, 0.5), Uniform(rng, -0.5, 0.5), 0.0, Uniform(rng, 0.08, 0.2)};
  // The hand sensors, drawn last so that every draw above stays what it was. Roll's absolute
  // encoder at any mounting angle; the jaw's Hall sensor either way round, its span 2100-2700
  // counts; the pedal's travel 2200-3400 counts.
  p.roll_sensor_offset_rad = Uniform(rng, -std::numbers::pi, std::numbers::pi);
  const bool jaw_up = rng() % 2 == 0;
  p.hand_sensors.jaw_closed_counts = jaw_up ? Uniform(rng, 300.0, 700.0) : Uniform(rng, 3400.0, 3800.0);
  p.hand_sensors.jaw_counts_per_rad = (jaw_up ? 1.0 : -1.0) * Uniform(rng, 3500.0, 4500.0);
  p.hand_sensors.pedal_up_counts = Uniform(rng, 200.0, 600.0);
  p.hand_sensors.pedal_down_counts = Uniform(rng, 2800.0, 3600.0);
  return t;
}

Joint4 MovedWhileOff(const ArmPlantParameters& plant, const Joint4& from, double distance_rad, std::uint64_t seed) {
  std::mt19937_64 rng(seed ^ 0x6d6f766564ULL);  // its own stream: the arm's draws stay as they are
  Joint4 q = from;
  for (int m = 0; m < 3; ++m) {
    const int joint = JointOfMotor(m);
    const double step = m < 2 ? distance_rad : 0.1 * distance_rad;
    const double clearance = m < 2 ? 0.05 : 0.005;
    const double sign = rng() % 2 == 0 ? 1.0 : -1.0;
    double to = from[joint] + sign * step;
    if (to < plant.lower_limit[joint] + clearance || to > plant.upper_limit[joint] - clearance)
      to = from[joint] - sign * step;
    q[joint] = to;
  }
  return q;
}

}  // namespace vesica::fp::emulator
