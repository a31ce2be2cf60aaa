// The static obstacles' signed distances (physics/scene/static_obstacles.h,
// physics/collision/ellipsoid_distance.h, physics/collision/surface_proximity_grid.h) against
// independent references: closed forms for spheres and capsules, dense sampling of an
// ellipsoid's surface, brute force over every triangle of a mesh.

#include "physics/scene/static_obstacles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>

#include "physics/collision/ellipsoid_distance.h"
#include "physics/collision/surface_proximity_grid.h"
#include "physics/mesh/barycentric.h"
#include "physics/mesh/primitives.h"

namespace vesica::physics {
namespace {

TEST(EllipsoidDistance, SphereIsRadialDistance) {
  const Eigen::Vector3d c(0.01, -0.02, 0.03);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d p = c + Eigen::Vector3d(u(rng), u(rng), u(rng));
    const EllipsoidSurfacePoint s = ClosestPointOnEllipsoid(c, Eigen::Vector3d::Constant(0.02), p);
    EXPECT_NEAR(s.signed_distance_m, (p - c).norm() - 0.02, 1e-12);
    EXPECT_NEAR((s.normal_W - (p - c).normalized()).norm(), 0.0, 1e-9);
  }
}

TEST(EllipsoidDistance, MatchesDenseSamplingOfTheSurface) {
  const Eigen::Vector3d c(0.0, 0.01, -0.02), e(0.04, 0.015, 0.025);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.06, 0.06);
  for (int k = 0; k < 20; ++k) {
    const Eigen::Vector3d p = c + Eigen::Vector3d(u(rng), u(rng), u(rng));
    const EllipsoidSurfacePoint s = ClosestPointOnEllipsoid(c, e, p);
    // On the surface, with p - x along the normal there (the closest point's conditions).
    EXPECT_NEAR((s.p_Surface_W - c).cwiseQuotient(e).norm(), 1.0, 1e-12);
    EXPECT_LT(((p - s.p_Surface_W) - s.normal_W * s.normal_W.dot(p - s.p_Surface_W)).norm(), 1e-10);
    // No sampled surface point (1/4 degree grid) is nearer than it (sampling error < 0.2 mm here).
    double nearest = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= 720; ++i)
      for (int j = 0; j < 1440; j += 1) {
        const double th = std::numbers::pi * i / 720, ph = 2 * std::numbers::pi * j / 1440;
        const Eigen::Vector3d q =
            c + e.cwiseProduct(Eigen::Vector3d(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)));
        nearest = std::min(nearest, (p - q).norm());
      }
    EXPECT_LE(std::abs(s.signed_distance_m), nearest + 1e-12);
    EXPECT_NEAR(std::abs(s.signed_distance_m), nearest, 2e-4);
    EXPECT_EQ(s.signed_distance_m < 0, (p - c).cwiseQuotient(e).norm() < 1.0);
  }
}

TEST(EllipsoidDistance, PointsOnTheAxesAndTheCentre) {
  const Eigen::Vector3d c = Eigen::Vector3d::Zero(), e(0.04, 0.02, 0.03);
  // Outside on an axis: the axis's end is nearest.
  EXPECT_NEAR(ClosestPointOnEllipsoid(c, e, {0.0, 0.05, 0.0}).signed_distance_m, 0.03, 1e-12);
  EXPECT_NEAR(ClosestPointOnEllipsoid(c, e, {-0.07, 0.0, 0.0}).signed_distance_m, 0.03, 1e-12);
  // The centre, where all three axes' roots meet (the nudge off the planes costs a micrometre):
  // the shortest semi-axis away, inside.
  EXPECT_NEAR(ClosestPointOnEllipsoid(c, e, c).signed_distance_m, -0.02, 1e-6);
}

TEST(StaticObstacles, TubeIsTheUnionOfCapsules) {
  const ObstacleTube tube{"bowel", {{0, 0, 0}, {0.1, 0, 0}, {0.1, 0.1, 0}}, 0.01};
  EXPECT_NEAR(TubeProximity(tube, {0.05, 0.03, 0}).signed_distance_m, 0.02, 1e-15);  // beside segment 0
  EXPECT_NEAR(TubeProximity(tube, {0.05, -0.005, 0}).signed_distance_m, -0.005, 1e-15);
  EXPECT_NEAR(TubeProximity(tube, {-0.03, 0, 0.04}).signed_distance_m, 0.04, 1e-15);  // past the end cap
  EXPECT_NEAR(TubeProximity(tube, {0.13, 0.05, 0}).signed_distance_m, 0.02, 1e-15);   // beside segment 1
  const ObstacleProximity q = TubeProximity(tube, {0.05, 0.03, 0});
  EXPECT_NEAR((q.normal_W - Eigen::Vector3d::UnitY()).norm(), 0.0, 1e-15);
  EXPECT_NEAR((q.p_Surface_W - Eigen::Vector3d(0.05, 0.01, 0)).norm(), 0.0, 1e-15);
}

TEST(StaticObstacles, NearestObstacleKeepsTheBandAndTheDeepest) {
  StaticObstacles obstacles;
  obstacles.ellipsoids.push_back({"stomach", {0, 0, 0}, {0.02, 0.02, 0.02}});
  obstacles.tubes.push_back({"colon", {{-0.1, 0.03, 0}, {0.1, 0.03, 0}}, 0.005});
  // 1 mm over the sphere and 4 mm under the tube: both within a 5 mm margin.
  auto near = NearestObstacle(obstacles, {0, 0.021, 0}, 0.005, 0.008);
  ASSERT_TRUE(near);
  EXPECT_NEAR(near->signed_distance_m, 0.001, 1e-12);  // the sphere (1 mm) is nearer than the tube (4 mm)
  EXPECT_FALSE(NearestObstacle(obstacles, {0, 0.05, 0}, 0.005, 0.008));  // 15 mm from the tube
  EXPECT_FALSE(NearestObstacle(obstacles, {0, 0.0, 0}, 0.005, 0.008));   // 20 mm deep in the sphere: left alone
  near = NearestObstacle(obstacles, {0, 0.019, 0}, 0.001, 0.008);
  ASSERT_TRUE(near);
  EXPECT_NEAR(near->signed_distance_m, -0.001, 1e-12);
  EXPECT_NEAR(near->normal_W.y(), 1.0, 1e-12);
}

TEST(StaticObstacles, BadObstaclesAreNamed) {
  auto message = [](const StaticObstacles& o) {
    try {
      CheckStaticObstacles(o);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  StaticObstacles one_point;
  one_point.tubes.push_back({"duodenum", {{0, 0, 0}}, 0.01});
  EXPECT_NE(message(one_point).find("tube 'duodenum': needs at least 2"), std::string::npos) << message(one_point);
  StaticObstacles flat;
  flat.ellipsoids.push_back({"omentum", {0, 0, 0}, {0.1, 0.0, 0.05}});
  EXPECT_NE(message(flat).find("ellipsoid 'omentum': semi-axes"), std::string::npos) << message(flat);
  StaticObstacles doubled;
  doubled.tubes.push_back({"colon", {{0, 0, 0}, {0, 0, 0}}, 0.02});
  EXPECT_NE(message(doubled).find("points 0 and 1 coincide"), std::string::npos) << message(doubled);
  StaticObstacles thin;
  thin.tubes.push_back({"colon", {{0, 0, 0}, {0, 0, 1}}, -0.02});
  EXPECT_NE(message(thin).find("tube 'colon': radius"), std::string::npos) << message(thin);
  StaticObstacles nan;
  nan.tubes.push_back({"colon", {{0, 0, 0}, {0, std::nan(""), 1}}, 0.02});
  EXPECT_NE(message(nan).find("point 1 is not finite"), std::string::npos) << message(nan);
}

TEST(SurfaceProximityGrid, MatchesBruteForceOverEveryTriangle) {
  const TriangleMesh sphere = MakeIcosphere(0.03, 3);
  const SurfaceProximityGrid grid(sphere, 0.012, 0.008);
  // The surface moved 4 mm (less than reach - band) and squashed: queries use the current vertices.
  Vertices moved = sphere.vertices;
  moved.col(1) *= 0.9;
  moved.col(0).array() += 0.004;
  const SurfaceProximityGrid::Frame frame = grid.MakeFrame(moved);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.045, 0.045);
  int found = 0;
  for (int k = 0; k < 2000; ++k) {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    double best = std::numeric_limits<double>::infinity();
    int best_f = -1;
    for (int f = 0; f < sphere.num_triangles(); ++f) {
      const TrianglePoint cp = ClosestPointOnTriangle(p, moved.row(sphere.triangles(f, 0)).transpose(),
                                                      moved.row(sphere.triangles(f, 1)).transpose(),
                                                      moved.row(sphere.triangles(f, 2)).transpose());
      if ((p - cp.point).norm() < best) best = (p - cp.point).norm(), best_f = f;
    }
    const auto near = grid.Nearest(p, frame, 0.006);
    if (best > 0.006) {
      EXPECT_FALSE(near) << "point " << k;
      continue;
    }
    ASSERT_TRUE(near) << "point " << k << " at " << best << " m";
    ++found;
    EXPECT_NEAR(std::abs(near->signed_distance_m), best, 1e-15);
    // Inside the squashed sphere (an ellipsoid through the moved vertices, to the facets' sag): negative.
    const Eigen::Vector3d local = p - Eigen::Vector3d(0.004, 0, 0);
    const double implicit = local.cwiseQuotient(Eigen::Vector3d(0.03, 0.027, 0.03)).norm();
    if (std::abs(implicit - 1.0) > 0.05) {
      EXPECT_EQ(near->signed_distance_m < 0, implicit < 1.0) << "point " << k;
    }
    (void)best_f;
  }
  EXPECT_GT(found, 100);
}

TEST(SurfaceProximityGrid, RefusesAnEmptySurfaceOrNoReach) {
  EXPECT_THROW(SurfaceProximityGrid(TriangleMesh{}, 0.01, 0.01), std::invalid_argument);
  EXPECT_THROW(SurfaceProximityGrid(MakeIcosphere(0.03, 1), 0.0, 0.01), std::invalid_argument);
}

}  // namespace
}  // namespace vesica::physics
