// The point/ray queries the anatomy tests rely on, against shapes with known answers.
#include "app/anatomy/surface_distance.h"

#include <gtest/gtest.h>

#include "physics/mesh/primitives.h"

namespace vesica::app::anatomy {
namespace {

TEST(SurfaceDistanceTest, ClosestPointOnTriangleInFaceEdgeAndCorner) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_TRUE(ClosestPointOnTriangle({0.2, 0.2, 3}, a, b, c).isApprox(Eigen::Vector3d(0.2, 0.2, 0)));
  EXPECT_TRUE(ClosestPointOnTriangle({0.5, -2, 0}, a, b, c).isApprox(Eigen::Vector3d(0.5, 0, 0)));
  EXPECT_TRUE(ClosestPointOnTriangle({2, 2, 0}, a, b, c).isApprox(Eigen::Vector3d(0.5, 0.5, 0)));
  EXPECT_TRUE(ClosestPointOnTriangle({-1, -1, -1}, a, b, c).isApprox(a));
}

TEST(SurfaceDistanceTest, SphereDistanceInsideAndRayHit) {
  const physics::TriangleMesh sphere = physics::MakeIcosphere(0.05, 4);
  // The icosphere's flat facets sit at most about 0.1 mm inside the 5 cm sphere at this level.
  EXPECT_NEAR(DistanceToSurface(sphere, {0, 0, 0.08}), 0.03, 2e-4);
  EXPECT_NEAR(DistanceToSurface(sphere, {0, 0, 0}), 0.05, 2e-4);
  EXPECT_TRUE(IsInsideClosedSurface(sphere, {0.01, -0.02, 0.03}));
  EXPECT_FALSE(IsInsideClosedSurface(sphere, {0.04, 0.04, 0.04}));
  const auto hit = FirstRayHit(sphere, {0, -1, 0}, Eigen::Vector3d::UnitY());
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(*hit, 0.95, 2e-4);
  EXPECT_FALSE(FirstRayHit(sphere, {0, -1, 0}, -Eigen::Vector3d::UnitY()).has_value());
}

}  // namespace
}  // namespace vesica::app::anatomy
