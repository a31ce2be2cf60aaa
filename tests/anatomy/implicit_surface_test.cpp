// The §3.3 surface pipeline on a sphere, whose volume and radius are known.
#include "app/anatomy/implicit_surface.h"

#include <gtest/gtest.h>

#include <numbers>

#include "physics/mesh/mesh_validation.h"

namespace vesica::app::anatomy {
namespace {

constexpr double kRadius = 0.02;
const ImplicitField kSphere = [](const Eigen::Vector3d& p) { return p.norm() - kRadius; };
const Box kBox{Eigen::Vector3d::Constant(-kRadius), Eigen::Vector3d::Constant(kRadius)};
const double kVolume = 4.0 / 3.0 * std::numbers::pi * kRadius * kRadius * kRadius;

TEST(ImplicitSurfaceTest, MarchingCubesOfASphereIsClosedWithItsVolume) {
  const physics::TriangleMesh dense = ExtractIsosurface(kSphere, kBox, 0.001);
  EXPECT_NO_THROW(physics::ValidateTriangleMesh(dense, "sphere", physics::SurfaceRequirement::kAny));
  EXPECT_NEAR(std::abs(physics::EnclosedVolume(dense)), kVolume, 0.02 * kVolume);
}

TEST(ImplicitSurfaceTest, DecimatedSmoothedSphereKeepsShapeAndReachesTarget) {
  physics::TriangleMesh mesh = DecimateAndSmooth(ExtractIsosurface(kSphere, kBox, 0.001), {.target_vertices = 300});
  OrientOutward(mesh, kSphere);
  EXPECT_NO_THROW(physics::ValidateTriangleMesh(mesh, "sphere", physics::SurfaceRequirement::kClosed));
  EXPECT_NEAR(mesh.num_vertices(), 300, 30);
  EXPECT_NEAR(physics::EnclosedVolume(mesh), kVolume, 0.04 * kVolume);
  for (int i = 0; i < mesh.num_vertices(); ++i) EXPECT_NEAR(mesh.vertices.row(i).norm(), kRadius, 0.001);
}

TEST(ImplicitSurfaceTest, OrientOutwardFlipsAnInwardSurface) {
  physics::TriangleMesh mesh = DecimateAndSmooth(ExtractIsosurface(kSphere, kBox, 0.001), {.target_vertices = 200});
  OrientOutward(mesh, kSphere);
  mesh.triangles.col(1).swap(mesh.triangles.col(2));  // now inward
  ASSERT_LT(physics::EnclosedVolume(mesh), 0);
  OrientOutward(mesh, kSphere);
  EXPECT_GT(physics::EnclosedVolume(mesh), 0);
}

TEST(ImplicitSurfaceTest, ClipKeepsTheHalfTheNormalPointsTo) {
  const physics::TriangleMesh half = ClipKeepAbove(ExtractIsosurface(kSphere, kBox, 0.001), {0, 0, 0}, {0, 0, 1});
  ASSERT_GT(half.num_vertices(), 0);
  EXPECT_GE(half.vertices.col(2).minCoeff(), -1e-12);
  EXPECT_NEAR(half.vertices.col(2).maxCoeff(), kRadius, 0.001);
  EXPECT_THROW(physics::ValidateTriangleMesh(half, "half", physics::SurfaceRequirement::kClosed), physics::MeshError);
}

TEST(ImplicitSurfaceTest, RejectsBadParameters) {
  const physics::TriangleMesh dense = ExtractIsosurface(kSphere, kBox, 0.002);
  EXPECT_THROW(ExtractIsosurface(kSphere, kBox, 0.0), std::invalid_argument);
  EXPECT_THROW(DecimateAndSmooth(dense, {.target_vertices = 3}), std::invalid_argument);
  EXPECT_THROW(DecimateAndSmooth(dense, {.target_vertices = 100, .passband = 2.5}), std::invalid_argument);
}

}  // namespace
}  // namespace vesica::app::anatomy
