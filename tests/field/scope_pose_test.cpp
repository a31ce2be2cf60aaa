// The 30-degree laparoscope (issue 30): ScopePoseOf puts the tip on the scope's shaft, insertion_m
// in from the port, and looks scope_angle_deg off the shaft at look_at, the image's centre, the
// view coming down onto the field; a 0-degree scope looks along the port->look_at line as before.
// Checked by the geometry's own properties and against the independent camera of
// tests/app/screen_projection.h (bisection instead of the law of sines).

#include "app/render/scope_pose.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "../app/screen_projection.h"
#include "app/scenario/scenario_loader.h"

namespace vesica::app {
namespace {

double DegreesBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / std::numbers::pi;
}

LaparoscopeConfig Scope(const Eigen::Vector3d& port, const Eigen::Vector3d& look_at, double insertion_m,
                        double angle_deg) {
  LaparoscopeConfig s;
  s.position_m = port;
  s.look_at_m = look_at;
  s.insertion_m = insertion_m;
  s.scope_angle_deg = angle_deg;
  return s;
}

// The default scenario's scope, and others looking in other directions and from nearer.
std::vector<LaparoscopeConfig> Scopes(double angle_deg) {
  const LaparoscopeConfig def = LoadScenario(DefaultScenarioPath()).laparoscope;
  return {Scope(def.position_m, def.look_at_m, def.insertion_m, angle_deg),
          Scope({0.0, 0.1165, -0.1}, {-0.04, 0.0136, 0.0212}, 0.04, angle_deg),
          Scope({0.05, 0.10, 0.0}, {-0.03, 0.02, 0.06}, 0.09, angle_deg),
          Scope({0.0, 0.12, -0.1}, {0.0, 0.02, 0.1}, 0.15, angle_deg)};
}

TEST(ScopePose, TheLineOfSightLeavesTheShaftAtTheScopesAngle) {
  for (double angle : {30.0, 45.0, 10.0})
    for (const LaparoscopeConfig& s : Scopes(angle)) {
      const ScopePose p = ScopePoseOf(s);
      EXPECT_NEAR(DegreesBetween(p.shaft_W, p.forward_W), angle, 1e-9);
      EXPECT_NEAR(p.forward_W.norm(), 1.0, 1e-12);
      EXPECT_NEAR(p.up_W.norm(), 1.0, 1e-12);
      EXPECT_NEAR(p.up_W.dot(p.forward_W), 0.0, 1e-12);
    }
}

TEST(ScopePose, TheImageCentreRayHitsLookAt) {
  for (double angle : {0.0, 30.0, 45.0})
    for (const LaparoscopeConfig& s : Scopes(angle)) {
      const ScopePose p = ScopePoseOf(s);
      const Eigen::Vector3d to_look_at = s.look_at_m - p.eye_W;
      // look_at on the centre ray, in front of the lens: no sideways offset at all.
      EXPECT_GT(to_look_at.dot(p.forward_W), 0.0);
      EXPECT_NEAR((to_look_at - to_look_at.dot(p.forward_W) * p.forward_W).norm(), 0.0, 1e-12);
    }
}

TEST(ScopePose, TheTipIsInsertionFromThePortOnTheShaft) {
  for (double angle : {0.0, 30.0, 45.0})
    for (const LaparoscopeConfig& s : Scopes(angle)) {
      const ScopePose p = ScopePoseOf(s);
      EXPECT_NEAR((p.eye_W - s.position_m).norm(), s.insertion_m, 1e-12);
      EXPECT_NEAR((p.eye_W - s.position_m).normalized().cross(p.shaft_W).norm(), 0.0, 1e-12);
      EXPECT_GT((p.eye_W - s.position_m).dot(p.shaft_W), 0.0);
    }
}

TEST(ScopePose, TheThirtyDegreeScopeLooksDownOntoTheFieldAndKeepsTheHorizon) {
  const LaparoscopeConfig s = LoadScenario(DefaultScenarioPath()).laparoscope;
  ASSERT_DOUBLE_EQ(s.scope_angle_deg, 30.0);
  const ScopePose p = ScopePoseOf(s);
  const Eigen::Vector3d line = (s.look_at_m - s.position_m).normalized();
  // The shaft is held above the port->look_at line (toward the anterior wall), in the plane of
  // that line and the wall; the optic looks down from it: the tip is more anterior than a
  // straight scope's, and the line of sight falls more steeply than the line.
  const Eigen::Vector3d straight_eye = s.position_m + s.insertion_m * line;
  EXPECT_GT(p.eye_W.y(), straight_eye.y() + 0.01);
  EXPECT_LT(p.forward_W.y(), line.y());
  EXPECT_NEAR(p.shaft_W.dot(line.cross(Eigen::Vector3d::UnitY()).normalized()), 0.0, 1e-12);
  // The horizon: the wall at the top (image up has no component to the patient's side beyond
  // what the line of sight forces: up is +y made orthogonal to forward).
  const Eigen::Vector3d wall_up = (Eigen::Vector3d::UnitY() - p.forward_W.y() * p.forward_W).normalized();
  EXPECT_NEAR((p.up_W - wall_up).norm(), 0.0, 1e-12);
}

TEST(ScopePose, AZeroDegreeScopeIsTheStraightScopeExactly) {
  for (const LaparoscopeConfig& s : Scopes(0.0)) {
    const ScopePose p = ScopePoseOf(s);
    // The straight scope, as it was computed before the angled optic.
    const Eigen::Vector3d forward = (s.look_at_m - s.position_m).normalized();
    const Eigen::Vector3d eye = s.position_m + s.insertion_m * forward;
    const Eigen::Vector3d up =
        (Eigen::Vector3d::UnitY() - Eigen::Vector3d::UnitY().dot(forward) * forward).normalized();
    EXPECT_EQ(p.forward_W, forward);
    EXPECT_EQ(p.eye_W, eye);
    EXPECT_EQ(p.up_W, up);
    EXPECT_EQ(p.shaft_W, forward);
  }
}

TEST(ScopePose, AgreesWithTheTestsIndependentCamera) {
  for (double angle : {0.0, 30.0, 45.0, -30.0})
    for (const LaparoscopeConfig& s : Scopes(angle)) {
      const ScopePose p = ScopePoseOf(s);
      const testing::ScopeCamera c = testing::CameraOf(s);
      EXPECT_NEAR((p.eye_W - c.eye).norm(), 0.0, 1e-9) << angle;
      EXPECT_NEAR((p.forward_W - c.forward).norm(), 0.0, 1e-9) << angle;
      EXPECT_NEAR((p.up_W - c.up).norm(), 0.0, 1e-9) << angle;
    }
}

TEST(ScopePose, ALookAtPointBehindTheTipOrABadAngleIsRefusedByName) {
  const LaparoscopeConfig def = LoadScenario(DefaultScenarioPath()).laparoscope;
  LaparoscopeConfig deep = def;
  deep.insertion_m = (def.look_at_m - def.position_m).norm() + 0.01;
  try {
    ScopePoseOf(deep);
    FAIL() << "the tip past look_at was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("insertion_m"), std::string::npos) << e.what();
  }
  LaparoscopeConfig sideways = def;
  sideways.scope_angle_deg = 90;
  try {
    ScopePoseOf(sideways);
    FAIL() << "a 90-degree optic was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("scope_angle_deg"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vesica::app
