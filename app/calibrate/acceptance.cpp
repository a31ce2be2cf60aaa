#include "app/calibrate/acceptance.h"

#include <algorithm>
#include <cmath>

namespace vesica::app::calibrate {
namespace {

bool Ran(const std::vector<Step>& steps, Step s) { return std::find(steps.begin(), steps.end(), s) != steps.end(); }

void Add(std::vector<Check>& out, std::string name, std::string unit, double value, double lo, double hi) {
  out.push_back({std::move(name), std::move(unit), value, lo, hi, value >= lo && value <= hi});
}

// |measured - stored| within tol, shown as the difference.
void AddDiff(std::vector<Check>& out, std::string name, std::string unit, double measured, double stored, double tol) {
  Add(out, std::move(name), std::move(unit), measured - stored, -tol, tol);
}

}  // namespace

const char* JointName(int j) { return j == 0 ? "yaw" : j == 1 ? "pitch" : "insertion"; }

std::vector<Check> AcceptanceChecks(const device::calibration::CalibrationResult& r, unsigned joints,
                                    const std::vector<Step>& steps) {
  std::vector<Check> c;
  for (int j = 0; j < 3; ++j) {
    if (!((joints >> j) & 1u)) continue;
    const bool rotary = j < 2;
    const std::string n = JointName(j);
    const std::string length = rotary ? "rad" : "m";
    const std::string force = rotary ? "N m" : "N";
    const auto& jc = r.joint[j];
    const double centre = rotary ? 0.0 : 0.135;  // design centre: the stops are symmetric about it
    // Windows: the arm's design (stops 2.0-2.2 rad or 220-240 mm apart, friction of its gears
    // and seals, sensor offsets within the amplifier's spec) with room either side.
    if (Ran(steps, Step::kCurrentOffset)) Add(c, n + ".current_offset", "A", jc.current_offset_A, -0.1, 0.1);
    if (Ran(steps, Step::kEncoderDirection)) Add(c, n + ".direction", "", jc.direction, -1, 1);
    if (Ran(steps, Step::kRange)) {
      Add(c, n + ".range_span", length, jc.upper_stop - jc.lower_stop, rotary ? 1.9 : 0.21, rotary ? 2.3 : 0.25);
      // The zero is the stops' midpoint: the stops must straddle it.
      const double hmin = rotary ? 0.9 : 0.1, hmax = rotary ? 1.2 : 0.13;
      Add(c, n + ".lower_stop", length, jc.lower_stop, centre - hmax, centre - hmin);
      Add(c, n + ".upper_stop", length, jc.upper_stop, centre + hmin, centre + hmax);
    }
    if (Ran(steps, Step::kIndex)) {
      const double half_spacing = rotary ? 3.141592653589793 / 14.0 : 3.141592653589793 / 100.0;
      Add(c, n + ".index_position", length, jc.index_position, centre - half_spacing, centre + half_spacing);
    }
    if (Ran(steps, Step::kFriction)) {
      Add(c, n + ".coulomb", force, jc.coulomb, rotary ? 0.002 : 0.1, rotary ? 0.02 : 1.0);
      Add(c, n + ".viscous", force + (rotary ? " s/rad" : " s/m"), jc.viscous, rotary ? 0.001 : 0.25,
          rotary ? 0.01 : 2.5);
      // A straight Coulomb + viscous line must explain the sweeps.
      Add(c, n + ".friction_rms", force, jc.friction_rms, 0.0, 0.3 * std::max(jc.coulomb, 1e-9));
    }
    // The motor's torque constant over the node's parameter: a motor within its datasheet's
    // +-10 % (the check measures it within 1 %: docs/calibration.md).
    if (Ran(steps, Step::kTorqueConstant)) Add(c, n + ".torque_constant_ratio", "", jc.torque_constant_ratio, 0.9, 1.1);
  }
  if (((joints >> 1) & 1u) && Ran(steps, Step::kGravity))
    Add(c, "pitch.gravity_amplitude", "N m", std::hypot(r.gravity_sin, r.gravity_cos), 0.0, 0.08);
  // The hand sensors: a span or travel the step already insisted on (500 counts of 4096).
  const auto& h = r.hand;
  if (Ran(steps, Step::kRollOffset)) Add(c, "roll.sensor_offset", "rad", h.roll_offset_rad, -3.1416, 3.1416);
  if (Ran(steps, Step::kJawSpan)) Add(c, "jaw.span", "counts", std::abs(h.jaw_open_raw - h.jaw_closed_raw), 500, 4095);
  if (Ran(steps, Step::kPedalTravel))
    Add(c, "pedal.travel", "counts", std::abs(h.pedal_down_raw - h.pedal_up_raw), 500, 4095);
  return c;
}

std::vector<Check> VerifyChecks(const device::calibration::CalibrationResult& r, const CalibrationValues& stored,
                                unsigned joints, const std::vector<Step>& steps,
                                const std::array<double, 3>& range_margin) {
  std::vector<Check> c;
  for (int j = 0; j < 3; ++j) {
    if (!((joints >> j) & 1u)) continue;
    const bool rotary = j < 2;
    const std::string n = JointName(j);
    const std::string length = rotary ? "rad" : "m";
    const auto& m = r.joint[j];
    const auto& s = stored.joint[j];
    if (Ran(steps, Step::kCurrentOffset))
      AddDiff(c, n + ".current_offset", "A", m.current_offset_A, s.current_offset_A, 0.01);
    if (Ran(steps, Step::kEncoderDirection)) AddDiff(c, n + ".direction", "", m.direction, s.direction, 0.0);
    if (Ran(steps, Step::kRange)) {
      // 0.5 degree or 0.5 mm, as the calibration's own accuracy.
      const double tol = rotary ? 0.5 * 3.141592653589793 / 180.0 : 0.5e-3;
      AddDiff(c, n + ".position_offset", length, m.position_offset, s.position_offset, tol);
      AddDiff(c, n + ".lower_stop", length, m.lower_stop + range_margin[j], s.joint_min, tol);
      AddDiff(c, n + ".upper_stop", length, m.upper_stop - range_margin[j], s.joint_max, tol);
    }
    if (Ran(steps, Step::kIndex))
      AddDiff(c, n + ".index_position", length, m.index_position, s.index_position, rotary ? 0.002 : 0.05e-3);
    if (Ran(steps, Step::kFriction)) {
      AddDiff(c, n + ".coulomb", rotary ? "N m" : "N", m.coulomb, s.coulomb, 0.1 * std::abs(s.coulomb) + 1e-6);
      AddDiff(c, n + ".viscous", rotary ? "N m s/rad" : "N s/m", m.viscous, s.viscous,
              0.1 * std::abs(s.viscous) + 1e-6);
    }
  }
  for (int j = 0; j < 3; ++j)
    if (((joints >> j) & 1u) && Ran(steps, Step::kTorqueConstant))
      Add(c, std::string(JointName(j)) + ".torque_constant_ratio", "", r.joint[j].torque_constant_ratio, 0.9, 1.1);
  if (((joints >> 1) & 1u) && Ran(steps, Step::kGravity)) {
    const double amplitude = std::hypot(stored.gravity_sin, stored.gravity_cos);
    AddDiff(c, "pitch.gravity_sin", "N m", r.gravity_sin, stored.gravity_sin, 0.1 * amplitude + 1e-4);
    AddDiff(c, "pitch.gravity_cos", "N m", r.gravity_cos, stored.gravity_cos, 0.1 * amplitude + 1e-4);
  }
  return c;
}

bool AllPass(const std::vector<Check>& checks) {
  return std::all_of(checks.begin(), checks.end(), [](const Check& c) { return c.pass; });
}

}  // namespace vesica::app::calibrate
