#include "physics/collision/surface_ray_caster.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "physics/mesh/mesh_topology.h"
#include "physics/mesh/primitives.h"

namespace vesica::physics {
namespace {

// Unit-ish box surface [0,0.04]x[0,0.04]x[0,0.02] m: flat faces give exact analytic hits.
TriangleMesh BoxSurface() { return ExtractBoundary(MakeBoxTetMesh({0.04, 0.04, 0.02}, {4, 4, 2})).surface; }

Eigen::Vector3d Reconstruct(const TriangleMesh& m, const SurfaceHit& h) {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) x += h.weights[k] * m.vertices.row(m.triangles(h.triangle, k)).transpose();
  return x;
}

TEST(SurfaceRayCasterTest, HitsBoxFaceAtAnalyticPoint) {
  const TriangleMesh box = BoxSurface();
  SurfaceRayCaster caster;
  const int id = caster.AddSurface(box);
  const auto hit = caster.FirstHit({{0.013, 0.027, -0.01}, {0.013, 0.027, 0.05}});
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->surface, id);
  EXPECT_NEAR(hit->distance, 0.01, 1e-12);
  EXPECT_TRUE(hit->point.isApprox(Eigen::Vector3d(0.013, 0.027, 0.0), 1e-12));
  EXPECT_TRUE(hit->normal.isApprox(Eigen::Vector3d(0, 0, -1), 1e-12));
  EXPECT_FALSE(hit->from_inside);
  EXPECT_NEAR(hit->weights.sum(), 1.0, 1e-12);
  EXPECT_TRUE(Reconstruct(box, *hit).isApprox(hit->point, 1e-12));
}

TEST(SurfaceRayCasterTest, HitsIcosphereNearItsRadius) {
  const TriangleMesh sphere = MakeIcosphere(0.05, 3);
  SurfaceRayCaster caster;
  caster.AddSurface(sphere);
  const Eigen::Vector3d dir = Eigen::Vector3d(1, 2, 3).normalized();
  const auto hit = caster.FirstHit({0.2 * dir, Eigen::Vector3d::Zero()});
  ASSERT_TRUE(hit.has_value());
  // Flat facets lie inside the sphere: the chord sag at level 3 is well under 1% of the radius.
  EXPECT_LE(hit->point.norm(), 0.05 + 1e-12);
  EXPECT_GE(hit->point.norm(), 0.05 * 0.99);
  EXPECT_NEAR(hit->distance, 0.2 - hit->point.norm(), 1e-12);
  EXPECT_GT(hit->normal.dot(dir), 0.95);  // outward normal faces the incoming ray
  EXPECT_TRUE(Reconstruct(sphere, *hit).isApprox(hit->point, 1e-12));
}

TEST(SurfaceRayCasterTest, HitFollowsRefittedVertices) {
  TriangleMesh box = BoxSurface();
  SurfaceRayCaster caster;
  const int id = caster.AddSurface(box);
  const ToolSegment seg{{0.02, 0.02, -0.05}, {0.02, 0.02, 0.2}};
  // Move the box up by 0.1 m and squash it: far outside the original BVH bounds.
  Vertices moved = box.vertices;
  moved.col(2) = moved.col(2) * 0.5 + Eigen::VectorXd::Constant(moved.rows(), 0.1);
  caster.UpdateVertices(id, moved);
  const auto hit = caster.FirstHit(seg);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->distance, 0.15, 1e-12);
  EXPECT_NEAR(hit->point.z(), 0.1, 1e-12);
  // And a segment through where the box used to be now misses.
  EXPECT_FALSE(caster.FirstHit({{0.02, 0.02, -0.05}, {0.02, 0.02, 0.05}}).has_value());
}

TEST(SurfaceRayCasterTest, MissesBesideAndShortOfTheSurface) {
  SurfaceRayCaster caster;
  caster.AddSurface(BoxSurface());
  EXPECT_FALSE(caster.FirstHit({{0.05, 0.02, -0.01}, {0.05, 0.02, 0.05}}).has_value());
  EXPECT_FALSE(caster.FirstHit({{0.02, 0.02, -0.03}, {0.02, 0.02, -0.001}}).has_value());
}

TEST(SurfaceRayCasterTest, SegmentStartingInsideHitsTheExitFace) {
  SurfaceRayCaster caster;
  caster.AddSurface(BoxSurface());
  const auto hit = caster.FirstHit({{0.015, 0.025, 0.01}, {0.015, 0.025, 0.05}});
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->distance, 0.01, 1e-12);
  EXPECT_NEAR(hit->point.z(), 0.02, 1e-12);
  EXPECT_TRUE(hit->from_inside);
  EXPECT_TRUE(hit->normal.isApprox(Eigen::Vector3d(0, 0, 1), 1e-12));
}

TEST(SurfaceRayCasterTest, NearestOfTwoSurfacesWins) {
  SurfaceRayCaster caster;
  TriangleMesh low = BoxSurface();
  TriangleMesh high = low;
  high.vertices.col(2).array() += 0.05;
  const int high_id = caster.AddSurface(high);
  const int low_id = caster.AddSurface(low);
  const auto down = caster.FirstHit({{0.02, 0.02, 0.2}, {0.02, 0.02, -0.1}});
  ASSERT_TRUE(down.has_value());
  EXPECT_EQ(down->surface, high_id);
  EXPECT_NEAR(down->distance, 0.2 - 0.07, 1e-12);
  const auto up = caster.FirstHit({{0.02, 0.02, -0.1}, {0.02, 0.02, 0.2}});
  ASSERT_TRUE(up.has_value());
  EXPECT_EQ(up->surface, low_id);
}

TEST(SurfaceRayCasterTest, RejectsBadInput) {
  SurfaceRayCaster caster;
  EXPECT_THROW(caster.AddSurface(TriangleMesh{}), std::invalid_argument);
  TriangleMesh bad = BoxSurface();
  bad.triangles(3, 1) = 10000;
  EXPECT_THROW(caster.AddSurface(bad), std::invalid_argument);
  const int id = caster.AddSurface(BoxSurface());
  EXPECT_THROW(caster.UpdateVertices(id, Vertices::Zero(3, 3)), std::invalid_argument);
  EXPECT_THROW(caster.UpdateVertices(id + 1, Vertices::Zero(3, 3)), std::out_of_range);
  EXPECT_THROW(caster.FirstHit(id, {Eigen::Vector3d::Constant(NAN), Eigen::Vector3d::Zero()}), std::invalid_argument);
}

}  // namespace
}  // namespace vesica::physics
