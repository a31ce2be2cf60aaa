#include "physics/bem/bem_model.h"

#include <gtest/gtest.h>

#include "bem_test_support.h"
#include "physics/bem/bem_errors.h"
#include "physics/mesh/mesh_validation.h"

namespace vesica::physics {
namespace {

using testing::LiverLikeEllipsoid;

TEST(BemModelTest, RejectsOpenInwardAndNonManifoldSurfacesWithMeshError) {
  const TriangleMesh good = LiverLikeEllipsoid(60);
  TriangleMesh open = good;
  open.triangles.conservativeResize(open.num_triangles() - 1, 3);
  EXPECT_THROW(PrecomputeBemModel(open, LiverMaterial(), "open.obj"), MeshError);
  TriangleMesh inward = good;
  inward.triangles.col(1).swap(inward.triangles.col(2));
  try {
    PrecomputeBemModel(inward, LiverMaterial(), "inward.obj");
    FAIL() << "inward normals accepted";
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find("inward.obj"), std::string::npos) << e.what();
  }
  TriangleMesh non_manifold = good;  // a triangle repeated: three faces on its edges
  non_manifold.triangles.conservativeResize(good.num_triangles() + 1, 3);
  non_manifold.triangles.row(good.num_triangles()) = good.triangles.row(0);
  EXPECT_THROW(PrecomputeBemModel(non_manifold, LiverMaterial(), "nonmanifold.obj"), MeshError);
}

TEST(BemModelTest, RejectsMissingOrDegenerateFixedRegionAndBadMaterial) {
  TriangleMesh mesh = LiverLikeEllipsoid(60);
  TriangleMesh unlabelled = mesh;
  unlabelled.vertex_labels.resize(0);
  EXPECT_THROW(PrecomputeBemModel(unlabelled, LiverMaterial(), "liver"), BemError);
  TriangleMesh two_fixed = mesh;
  two_fixed.vertex_labels.setZero();
  two_fixed.vertex_labels(0) = two_fixed.vertex_labels(1) = kLabelFixed;
  try {
    PrecomputeBemModel(two_fixed, LiverMaterial(), "liver");
    FAIL() << "two fixed vertices accepted";
  } catch (const BemError& e) {
    EXPECT_NE(std::string(e.what()).find("non-collinear"), std::string::npos) << e.what();
  }
  EXPECT_THROW(PrecomputeBemModel(mesh, ElasticMaterial{-1.0, 0.4, 1060.0}, "liver"), BemError);
  EXPECT_THROW(PrecomputeBemModel(mesh, ElasticMaterial{170e3, 0.5, 1060.0}, "liver"), BemError);
}

TEST(BemModelTest, LumpedAreasSumToSurfaceArea) {
  const TriangleMesh mesh = LiverLikeEllipsoid(120);
  const BemModel model = PrecomputeBemModel(mesh, LiverMaterial(), "liver");
  double area = 0;
  for (int f = 0; f < mesh.num_triangles(); ++f) area += TriangleArea(mesh, f);
  EXPECT_NEAR(model.lumped_area_m2.sum(), area, 1e-12 * area);
  EXPECT_EQ(model.greens.rows(), 3 * mesh.num_vertices());
  EXPECT_EQ(model.greens.cols(), 3 * static_cast<Eigen::Index>(model.layout.free_nodes.size()));
}

}  // namespace
}  // namespace vesica::physics
