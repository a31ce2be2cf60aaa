#include "physics/bem/graded_surface_refinement.h"

#include <gtest/gtest.h>

#include <vector>

#include "physics/mesh/mesh_validation.h"
#include "physics/mesh/primitives.h"

namespace vesica::physics {
namespace {

TriangleMesh LabelledSphere() {
  TriangleMesh sphere = MakeIcosphere(0.05, 2);
  sphere.vertex_labels = Eigen::VectorXi::Zero(sphere.num_vertices());
  for (int v = 0; v < sphere.num_vertices(); ++v)
    if (sphere.vertices(v, 2) < -0.03) sphere.vertex_labels(v) = kLabelFixed;
  return sphere;
}

TEST(GradedSurfaceRefinementTest, KeepsTheSurfaceClosedTheVolumeAndTheOldVertices) {
  const TriangleMesh sphere = LabelledSphere();
  const std::vector<double> radii = {0.04, 0.02, 0.01};
  const RefinedSurface refined = RefineTowardPoint(sphere, Eigen::Vector3d(0, 0, 0.05), radii);
  EXPECT_NO_THROW(ValidateTriangleMesh(refined.surface, "refined sphere", SurfaceRequirement::kClosed));
  EXPECT_NEAR(EnclosedVolume(refined.surface), EnclosedVolume(sphere), 1e-15);  // midpoints lie on the facets
  EXPECT_GT(refined.surface.num_vertices(), sphere.num_vertices());
  EXPECT_EQ(refined.surface.vertices.topRows(sphere.num_vertices()), sphere.vertices);
  // Each original triangle's area is shared out among its children exactly.
  Eigen::VectorXd area = Eigen::VectorXd::Zero(sphere.num_triangles());
  for (int f = 0; f < refined.surface.num_triangles(); ++f)
    area(refined.parent_triangle(f)) += TriangleArea(refined.surface, f);
  for (int f = 0; f < sphere.num_triangles(); ++f) EXPECT_NEAR(area(f), TriangleArea(sphere, f), 1e-15);
}

TEST(GradedSurfaceRefinementTest, RefinesOnlyNearThePointAndGradesItsEdges) {
  const TriangleMesh sphere = LabelledSphere();
  const Eigen::Vector3d top(0, 0, 0.05);
  const std::vector<double> radii = {0.03, 0.015};
  const RefinedSurface refined = RefineTowardPoint(sphere, top, radii);
  double near_edge = 1, far_edge = 0;
  for (int f = 0; f < refined.surface.num_triangles(); ++f) {
    const Eigen::Vector3d a = refined.surface.vertices.row(refined.surface.triangles(f, 0)).transpose();
    const Eigen::Vector3d b = refined.surface.vertices.row(refined.surface.triangles(f, 1)).transpose();
    if ((a - top).norm() < 0.005) near_edge = std::min(near_edge, (a - b).norm());
    if (a.z() < -0.04) far_edge = std::max(far_edge, (a - b).norm());
  }
  EXPECT_LT(near_edge, 0.3 * far_edge);  // two 1:4 splits near the top, none at the bottom
  // The fixed cap is untouched, so no new vertex is fixed.
  for (int v = sphere.num_vertices(); v < refined.surface.num_vertices(); ++v)
    EXPECT_EQ(refined.surface.vertex_labels(v), kLabelNone);
}

TEST(GradedSurfaceRefinementTest, AMidpointInsideTheFixedRegionStaysFixed) {
  const TriangleMesh sphere = LabelledSphere();
  const std::vector<double> radii = {0.03};
  const RefinedSurface refined = RefineTowardPoint(sphere, Eigen::Vector3d(0, 0, -0.05), radii);
  int fixed_new = 0;
  for (int v = sphere.num_vertices(); v < refined.surface.num_vertices(); ++v)
    if (refined.surface.vertex_labels(v) & kLabelFixed) {
      ++fixed_new;
      EXPECT_LT(refined.surface.vertices(v, 2), -0.03);
    }
  EXPECT_GT(fixed_new, 0);
}

TEST(GradedSurfaceRefinementTest, RefusesARadiusThatIsNotPositive) {
  const std::vector<double> radii = {0.01, -1.0};
  EXPECT_THROW(
      {
        try {
          RefineTowardPoint(LabelledSphere(), Eigen::Vector3d::Zero(), radii);
        } catch (const MeshError& e) {
          EXPECT_NE(std::string(e.what()).find("radius 1"), std::string::npos) << e.what();
          throw;
        }
      },
      MeshError);
}

}  // namespace
}  // namespace vesica::physics
