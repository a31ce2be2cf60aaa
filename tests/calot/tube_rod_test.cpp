// The tube rod against Euler-Bernoulli beam theory and its own invariants (docs/calot.md).
#include "physics/calot/tube_rod.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace vesica::physics::calot {
namespace {

// A stiff tube for the beam tests, so the deflections stay small (< 1 % of the length) and
// linear theory holds.
TubeMaterial BeamMaterial() {
  TubeMaterial m;
  m.youngs_modulus_Pa = 20e6;
  m.outer_radius_m = 0.0015;
  m.wall_thickness_m = 0.0005;
  m.mass_damping_per_s = 200.0;  // settle quickly: the tests look at equilibrium
  return m;
}

/// A straight rod along +x of `segments` segments over length_m, plus a ghost segment before x = 0:
/// nodes 0 (x = -l) and 1 (x = 0) are held, which clamps the root's slope.
TubeRod ClampedCantilever(int segments, double length_m, const TubeMaterial& material,
                          const TubeRodSettings& settings) {
  const double l = length_m / segments;
  RodPoints points(segments + 2, 3);
  for (int i = 0; i < segments + 2; ++i) points.row(i) << (i - 1) * l, 0.0, 0.0;
  TubeRod rod(points, {}, material, settings);
  rod.HoldFixed(0);
  rod.HoldFixed(1);
  return rod;
}

void Settle(TubeRod& rod, int steps) {
  for (int k = 0; k < steps; ++k) rod.Step();
}

double TipDeflectionUnderTipLoad(int segments, double length_m, double force_N) {
  TubeRod rod = ClampedCantilever(segments, length_m, BeamMaterial(), TubeRodSettings{});
  rod.SetExternalForce(rod.num_nodes() - 1, {0.0, 0.0, -force_N});
  Settle(rod, 3000);
  return -rod.positions_m()(rod.num_nodes() - 1, 2);
}

TEST(TubeRodTest, CantileverTipLoadDeflectionConvergesToEulerBernoulli) {
  const double length = 0.03, force = 2e-3;
  const TubeMaterial material = BeamMaterial();
  const double analytic =
      force * std::pow(length, 3) / (3.0 * material.youngs_modulus_Pa * SecondMomentOfArea_m4(material));
  ASSERT_LT(analytic, 0.01 * length);  // linear theory
  // First order in the node spacing: the clamped ghost edge holds the slope at its midpoint, so
  // the rod bends as if half a segment longer (docs/calot.md). Each halving of the spacing about
  // halves the error.
  double previous_error = 1e9;
  for (int segments : {8, 16, 32, 64}) {
    const double error = std::abs(TipDeflectionUnderTipLoad(segments, length, force) / analytic - 1.0);
    EXPECT_LT(error, 0.6 * previous_error) << segments << " segments";
    previous_error = error;
  }
  EXPECT_LT(previous_error, 0.03);
}

TEST(TubeRodTest, CantileverUnderOwnWeightConvergesToEulerBernoulli) {
  const double length = 0.03, g = 9.81;
  const TubeMaterial material = BeamMaterial();
  const double q = LinearDensity_kg_per_m(material) * g;  // N/m
  const double analytic =
      q * std::pow(length, 4) / (8.0 * material.youngs_modulus_Pa * SecondMomentOfArea_m4(material));
  ASSERT_LT(analytic, 0.01 * length);
  TubeRodSettings settings;
  settings.gravity_m_per_s2 = {0.0, 0.0, -g};
  double previous_error = 1e9;
  for (int segments : {8, 16, 32, 64}) {
    TubeRod rod = ClampedCantilever(segments, length, material, settings);
    Settle(rod, 3000);
    const double deflection = -rod.positions_m()(rod.num_nodes() - 1, 2);
    const double error = std::abs(deflection / analytic - 1.0);
    EXPECT_LT(error, 0.6 * previous_error) << segments << " segments";
    previous_error = error;
  }
  EXPECT_LT(previous_error, 0.04);
}

TEST(TubeRodTest, AxialStretchIsForceTimesLengthOverEA) {
  const double length = 0.04, force = 0.05;
  const TubeMaterial material = BeamMaterial();
  RodPoints points(11, 3);
  for (int i = 0; i < 11; ++i) points.row(i) << length * i / 10.0, 0.0, 0.0;
  TubeRod rod(points, {}, material, TubeRodSettings{});
  rod.HoldFixed(0);
  rod.SetExternalForce(10, {force, 0.0, 0.0});
  Settle(rod, 2000);
  const double analytic = force * length / (material.youngs_modulus_Pa * WallArea_m2(material));
  EXPECT_NEAR(rod.positions_m()(10, 0) - length, analytic, 1e-3 * analytic);
  EXPECT_NEAR(rod.positions_m()(5, 0) - 0.5 * length, 0.5 * analytic, 1e-3 * analytic);  // uniform strain
}

// A curved rod (the default cystic duct's centreline), clamped at one end and tied to a fixed
// neck at the other, released from a deformed state without damping: implicit Euler may only
// lose energy.
TEST(TubeRodTest, EnergyDoesNotGrowWithoutInput) {
  RodPoints rest(9, 3);
  for (int i = 0; i < 9; ++i) {
    const double t = i / 8.0;
    rest.row(i) << 0.03 * t, 0.006 * std::sin(std::numbers::pi * t), 0.002 * t * t;
  }
  TubeMaterial material;
  material.mass_damping_per_s = 0.0;
  TubeRod rod(rest, {}, material, TubeRodSettings{});
  rod.HoldFixed(0);
  rod.HoldFixed(1);
  rod.CoupleToTarget(8, rest.row(8).transpose());
  RodPoints start = rest;
  for (int i = 2; i < 8; ++i) start(i, 2) += 0.002 * std::sin(1.7 * i);
  TubeRod deformed(rest, start, RodPoints::Zero(9, 3), {}, material, TubeRodSettings{});
  deformed.HoldFixed(0);
  deformed.HoldFixed(1);
  deformed.CoupleToTarget(8, rest.row(8).transpose());
  auto total = [](const TubeRod& r) {
    return r.KineticEnergy_J() + r.StretchEnergy_J() + r.BendingEnergy_J() + r.CouplingEnergy_J();
  };
  const double initial = total(deformed);
  ASSERT_GT(initial, 0.0);
  double previous = initial;
  for (int k = 0; k < 400; ++k) {
    deformed.Step();
    const double now = total(deformed);
    EXPECT_LE(now, previous * (1.0 + 1e-9) + 1e-15) << "step " << k;
    previous = now;
  }
  EXPECT_LT(previous, 0.5 * initial);  // implicit Euler's damping is real, not only bounded
  // At rest in its rest shape it stays there: no energy from nothing.
  for (int k = 0; k < 100; ++k) rod.Step();
  EXPECT_LT(total(rod), 1e-18);
  EXPECT_LT((rod.positions_m() - rest).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(TubeRodTest, CoupledEndFollowsAPrescribedNeckMotion) {
  RodPoints rest(13, 3);
  for (int i = 0; i < 13; ++i) rest.row(i) << 0.0, -0.0025 * i, 0.0;  // 30 mm down from the hilum
  TubeRod rod(rest, {}, TubeMaterial{}, TubeRodSettings{});
  rod.HoldFixed(0);
  rod.HoldFixed(1);
  const Eigen::Vector3d neck0 = rest.row(12).transpose();
  rod.CoupleToTarget(12, neck0);
  double worst_gap = 0.0, peak_middle = 0.0;
  Eigen::Vector3d force_at_peak = Eigen::Vector3d::Zero();
  for (int k = 0; k < 400; ++k) {  // 2 s: the neck swings 5 mm sideways and 4 mm along, 1 Hz
    const double t = (k + 1) * rod.settings().time_step_s;
    const Eigen::Vector3d target = neck0 + Eigen::Vector3d(0.005 * std::sin(2 * std::numbers::pi * t),
                                                           -0.004 * std::sin(2 * std::numbers::pi * t), 0);
    rod.SetCouplingTarget(12, target);
    rod.Step();
    worst_gap = std::max(worst_gap, (rod.positions_m().row(12).transpose() - target).norm());
    if (std::abs(rod.positions_m()(6, 0)) > peak_middle) {
      peak_middle = std::abs(rod.positions_m()(6, 0));
      force_at_peak = rod.CouplingForceOnTarget_N(12);
    }
  }
  EXPECT_LT(worst_gap, 3e-4);             // the end stays on the neck
  EXPECT_GT(peak_middle, 0.0015);         // and the rod follows it, bending
  EXPECT_GT(force_at_peak.norm(), 1e-4);  // the rod pulls back on the neck
}

TEST(TubeRodTest, BadInputIsRefusedWithAMessage) {
  RodPoints one(1, 3);
  one.setZero();
  EXPECT_THROW(TubeRod(one, {}, TubeMaterial{}, TubeRodSettings{}), std::invalid_argument);
  RodPoints two(2, 3);
  two << 0, 0, 0, 0.01, 0, 0;
  TubeMaterial bad;
  bad.wall_thickness_m = 0.01;
  try {
    TubeRod rod(two, {}, bad, TubeRodSettings{});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("wall_thickness_m"), std::string::npos);
  }
  TubeRod rod(two, {}, TubeMaterial{}, TubeRodSettings{});
  EXPECT_THROW(rod.HoldFixed(5), std::out_of_range);
  EXPECT_THROW(rod.SetCouplingTarget(1, Eigen::Vector3d::Zero()), std::logic_error);
}

}  // namespace
}  // namespace vesica::physics::calot
