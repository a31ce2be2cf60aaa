// A calibration report's measured numbers against the random arm's ground truth, within issue 32's
// tolerances: directions right, offsets and index within 2 counts, stops within 0.5 degree or
// 0.5 mm, Coulomb and viscous friction and pitch gravity within 10 %, current offsets 0.1 mA.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "firmware_protocol/emulator/arm_ground_truth.h"
#include "firmware_protocol/node/parameter_table.h"

namespace vesica::app::calibrate::testing {

inline void ExpectMeasuredIsGroundTruth(const nlohmann::json& measured, const fp::emulator::ArmGroundTruth& t) {
  namespace emu = fp::emulator;
  constexpr double kDeg = std::numbers::pi / 180.0;
  constexpr const char* kJoint[3] = {"yaw", "pitch", "insertion"};
  const double park[3] = {0.0, 0.0, static_cast<double>(0.135f)};
  for (int j = 0; j < 3; ++j) {
    const auto& m = measured["joints"][kJoint[j]];
    const double count = t.count(j);
    const int dir_sign = m["direction"].get<int>();
    EXPECT_EQ(dir_sign, t.plant.encoder[j].direction) << kJoint[j];
    // The board reads park + whole counts since power-up: the true offset, half a count added.
    const double true_offset = t.power_up[emu::JointOfMotor(j)] - dir_sign * park[j] + 0.5 * count;
    EXPECT_LE(std::abs(m["position_offset"].get<double>() - true_offset), 2 * count) << kJoint[j];
    EXPECT_LE(std::abs(m["index_position"].get<double>() - t.reference_index(j)), 2 * count) << kJoint[j];
    const double range_tol = j < 2 ? 0.5 * kDeg : 0.5e-3;
    EXPECT_NEAR(m["lower_stop"].get<double>(), t.lower_stop(j), range_tol) << kJoint[j];
    EXPECT_NEAR(m["upper_stop"].get<double>(), t.upper_stop(j), range_tol) << kJoint[j];
    // Friction in the node's torque units (its nominal Kt): what a current really gives.
    const double kt = t.torque_constant_ratio(
        j, fp::find_parameter(static_cast<std::uint16_t>(fp::param::kTorqueConstant + j))->default_value);
    EXPECT_NEAR(m["coulomb"].get<double>(), t.coulomb(j) / kt, 0.10 * t.coulomb(j) / kt) << kJoint[j];
    EXPECT_NEAR(m["viscous"].get<double>(), t.viscous(j) / kt, 0.10 * t.viscous(j) / kt) << kJoint[j];
    EXPECT_NEAR(m["current_offset_A"].get<double>(), t.plant.current_sensor_offset_A[j], 1e-4) << kJoint[j];
  }
  // Gravity within 10 % of its amplitude over the pitch range.
  const double kt = t.torque_constant_ratio(1, fp::find_parameter(fp::param::kTorqueConstant + 1)->default_value);
  const double gs = -t.plant.pitch_gravity_sin_Nm / kt, gc = -t.plant.pitch_gravity_cos_Nm / kt;
  const double rs = measured["gravity"]["sin"].get<double>(), rc = measured["gravity"]["cos"].get<double>();
  double worst = 0.0;
  for (double a = t.lower_stop(1); a <= t.upper_stop(1); a += 0.01)
    worst = std::max(worst, std::abs(rs * std::sin(a) + rc * std::cos(a) - (gs * std::sin(a) + gc * std::cos(a))));
  EXPECT_LE(worst, 0.10 * std::hypot(gs, gc));
}

}  // namespace vesica::app::calibrate::testing
