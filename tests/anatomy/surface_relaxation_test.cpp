// Relaxation keeps a surface on its implicit shape and makes its triangles better shaped.
#include "app/anatomy/surface_relaxation.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "physics/mesh/mesh_validation.h"

namespace vesica::app::anatomy {
namespace {

double MinTriangleAngleDeg(const physics::TriangleMesh& mesh) {
  double worst = 180;
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d a = mesh.vertices.row(mesh.triangles(f, k));
      const Eigen::Vector3d b = mesh.vertices.row(mesh.triangles(f, (k + 1) % 3));
      const Eigen::Vector3d c = mesh.vertices.row(mesh.triangles(f, (k + 2) % 3));
      worst = std::min(worst, std::acos((b - a).normalized().dot((c - a).normalized())) * 180 / std::numbers::pi);
    }
  }
  return worst;
}

TEST(SurfaceRelaxationTest, StaysOnTheShapeAndImprovesTheWorstAngle) {
  // An ellipsoid, decimated hard: quadric decimation leaves skinny triangles.
  const ImplicitField field = [](const Eigen::Vector3d& p) {
    return 0.01 * (p.cwiseQuotient(Eigen::Vector3d(0.04, 0.02, 0.015)).squaredNorm() - 1);
  };
  const Box box{Eigen::Vector3d(-0.04, -0.02, -0.015), Eigen::Vector3d(0.04, 0.02, 0.015)};
  physics::TriangleMesh mesh = DecimateAndSmooth(ExtractIsosurface(field, box, 0.0008), {.target_vertices = 250});
  OrientOutward(mesh, field);
  const double before = MinTriangleAngleDeg(mesh);
  const int triangles = mesh.num_triangles();

  RelaxOntoField(mesh, field, 20);
  OrientOutward(mesh, field);
  EXPECT_NO_THROW(physics::ValidateTriangleMesh(mesh, "relaxed", physics::SurfaceRequirement::kClosed));
  EXPECT_EQ(mesh.num_triangles(), triangles) << "flips keep the triangle count";
  for (int i = 0; i < mesh.num_vertices(); ++i) EXPECT_NEAR(field(mesh.vertices.row(i)), 0.0, 1e-9);
  EXPECT_GT(MinTriangleAngleDeg(mesh), before);
}

}  // namespace
}  // namespace vesica::app::anatomy
