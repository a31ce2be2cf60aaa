// Issue 30: a freed gallbladder comes to rest on what lies below it. The synthetic scene
// (synthetic_dissection.h: a 30 x 20 x 30 mm gallbladder box hanging 2 mm under a liver box) with
// every spring cut and the instruments out of the way:
//   - gravity -y drops it onto an ellipsoid 5 mm below its bottom face: it settles on the
//     ellipsoid's analytic surface, and without the obstacle it falls through;
//   - gravity +y pushes it up into the liver's bed: it rests on the liver, not through it.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <limits>

#include "physics/collision/ellipsoid_distance.h"
#include "physics/scene/dissection_scene.h"
#include "tests/scene/synthetic_dissection.h"

namespace vesica::physics {
namespace {

using testing::kShiftX;
using testing::kShiftZ;

// The ellipsoid's top 5 mm under the gallbladder's bottom face (y = -22 mm), off its centre in x
// so the box lands on a slope and friction has to hold it.
const ObstacleEllipsoid kBelow{"stomach", {kShiftX + 0.006, -0.047, kShiftZ}, {0.04, 0.02, 0.04}};

struct DropResult {
  double lowest_gap_m = 0;  // the nearest node's signed distance to the ellipsoid at the end
  double deepest_m = 0;     // deepest any node got inside the ellipsoid over the run
  double final_speed_m_per_s = 0;
  double energy_rise_J = 0;  // most the total energy ever stood above its start
  double energy_drop_J = 0;  // total energy at the start minus at the end
  double liver_depth_m = 0;  // deepest node above the bed (y > 0: inside the liver box)
  double centroid_y_m = 0;
  int contacts = 0;
};

double MaxNodeSpeed(const FemBody& body) {
  double v = 0;
  const Eigen::VectorXd& vel = body.state().velocity_m_per_s;
  for (Eigen::Index n = 0; n < vel.size() / 3; ++n) v = std::max(v, vel.segment<3>(3 * n).norm());
  return v;
}

DropResult Drop(const Eigen::Vector3d& gravity, const StaticObstacles& obstacles, bool on_liver, double seconds,
                double friction = 0.4) {
  DissectionModelInputs in = testing::SyntheticDissectionInputs();
  in.settings.gravity_m_per_s2 = gravity;
  in.settings.gallbladder_rests_on_liver = on_liver;
  in.settings.obstacle_friction = friction;
  in.obstacles = obstacles;
  const auto model = BuildDissectionModel(in);
  DissectionScene scene(model);
  for (size_t s = 0; s < scene.tissue().springs.size(); ++s) scene.CutSpring(static_cast<int>(s));
  std::array<InstrumentPose, 2> away{};  // insertion 0: the tips 58 mm under the gallbladder
  const Eigen::VectorXd& mass = model->gallbladder->lumped_mass_kg;
  auto total_energy = [&] {
    // Energy() has the kinetic and elastic parts; gravity's potential is -sum m g . x.
    const Vertices x = scene.gallbladder().CurrentPositions();
    double potential = 0;
    for (Eigen::Index n = 0; n < x.rows(); ++n) potential -= mass[3 * n] * gravity.dot(x.row(n).transpose());
    return scene.Energy() + potential;
  };
  const double e0 = total_energy();
  DropResult run;
  const int steps = static_cast<int>(seconds / model->settings.time_step_s);
  for (int k = 0; k < steps; ++k) {
    const DissectionStepReport report = scene.Step(away);
    run.contacts = report.obstacle_contacts;
    run.energy_rise_J = std::max(run.energy_rise_J, total_energy() - e0);
    const Vertices x = scene.gallbladder().CurrentPositions();
    for (Eigen::Index n = 0; n < x.rows(); ++n) {
      run.deepest_m = std::max(
          run.deepest_m,
          -ClosestPointOnEllipsoid(kBelow.centre_W, kBelow.semi_axes_m, x.row(n).transpose()).signed_distance_m);
      run.liver_depth_m = std::max(run.liver_depth_m, x(n, 1));
    }
  }
  run.energy_drop_J = e0 - total_energy();
  const Vertices x = scene.gallbladder().CurrentPositions();
  run.lowest_gap_m = std::numeric_limits<double>::infinity();
  for (Eigen::Index n = 0; n < x.rows(); ++n)
    run.lowest_gap_m =
        std::min(run.lowest_gap_m,
                 ClosestPointOnEllipsoid(kBelow.centre_W, kBelow.semi_axes_m, x.row(n).transpose()).signed_distance_m);
  run.final_speed_m_per_s = MaxNodeSpeed(scene.gallbladder());
  run.centroid_y_m = x.col(1).mean();
  std::printf(
      "nearest node %.3f mm off the ellipsoid, deepest %.3f mm inside it, %.3f mm into the liver; fastest node "
      "%.3f mm/s; energy rose at most %.2e J, fell %.2e J; centroid y %.1f mm; %d nodes pressed\n",
      1e3 * run.lowest_gap_m, 1e3 * run.deepest_m, 1e3 * run.liver_depth_m, 1e3 * run.final_speed_m_per_s,
      run.energy_rise_J, run.energy_drop_J, 1e3 * run.centroid_y_m, run.contacts);
  return run;
}

StaticObstacles Below() {
  StaticObstacles o;
  o.ellipsoids.push_back(kBelow);
  return o;
}

TEST(GallbladderRest, SettlesOnAnEllipsoidBelow) {
  const DropResult run = Drop({0, -9.81, 0}, Below(), true, 3.0);
  EXPECT_GT(run.contacts, 3);
  EXPECT_LT(std::abs(run.lowest_gap_m), 0.2e-3);  // lying on the surface, within 0.2 mm
  EXPECT_LT(run.deepest_m, 0.5e-3);               // never more than 0.5 mm inside
  EXPECT_LT(run.final_speed_m_per_s, 1e-3);       // at rest: every node under 1 mm/s
  EXPECT_LT(run.energy_rise_J, 1e-6);             // contact adds no energy (0.018 kg box: 1 uJ is 5.7 um of height)
  EXPECT_GT(run.energy_drop_J, 0.0);
}

TEST(GallbladderRest, SameDropGivesBitIdenticalStates) {
  auto final_state = [] {
    DissectionModelInputs in = testing::SyntheticDissectionInputs();
    in.settings.gravity_m_per_s2 = {0, -9.81, 0};
    in.obstacles = Below();
    DissectionScene scene(BuildDissectionModel(in));
    for (size_t s = 0; s < scene.tissue().springs.size(); ++s) scene.CutSpring(static_cast<int>(s));
    for (int k = 0; k < 100; ++k) scene.Step({});  // through the landing (at about 0.08 s)
    return scene.gallbladder().state().displacement_m;
  };
  const Eigen::VectorXd a = final_state(), b = final_state();
  EXPECT_EQ(a, b);
}

TEST(GallbladderRest, WithoutFrictionItSlidesOffTheSlope) {
  const DropResult run = Drop({0, -9.81, 0}, Below(), true, 3.0, 0.0);
  EXPECT_LT(run.centroid_y_m, -0.1);  // landed 6 mm off the top, slid down the side and fell
  EXPECT_LT(run.deepest_m, 0.5e-3);   // without ever entering the ellipsoid
}

TEST(GallbladderRest, FallsThroughWithoutTheObstacle) {
  const DropResult run = Drop({0, -9.81, 0}, {}, true, 3.0);
  EXPECT_EQ(run.contacts, 0);
  EXPECT_GT(run.deepest_m, 0.015);    // passed through the ellipsoid (20 mm half-height)
  EXPECT_LT(run.centroid_y_m, -0.1);  // and on, in free fall
}

TEST(GallbladderRest, RestsAgainstTheLiverNotThroughIt) {
  const DropResult run = Drop({0, 9.81, 0}, {}, true, 2.0);
  EXPECT_GT(run.contacts, 3);
  EXPECT_LT(run.liver_depth_m, 0.5e-3);  // the bed is y = 0
  EXPECT_GT(run.liver_depth_m, -1e-3);   // and it got there (the top face started 2 mm below)
  EXPECT_LT(run.final_speed_m_per_s, 1e-3);
  const DropResult through = Drop({0, 9.81, 0}, {}, false, 2.0);
  EXPECT_GT(through.liver_depth_m, 0.01);
}

}  // namespace
}  // namespace vesica::physics
