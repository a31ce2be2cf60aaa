// Relaxation keeps a surface on its implicit shape and makes its triangles better shaped.
#include "app/anatomy/surface_relaxation.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
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

// Mean length of the edges whose midpoints satisfy `where`.
template <typename Where>
double MeanEdgeLength(const physics::TriangleMesh& mesh, Where where) {
  double sum = 0;
  int n = 0;
  for (int f = 0; f < mesh.num_triangles(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d a = mesh.vertices.row(mesh.triangles(f, k));
      const Eigen::Vector3d b = mesh.vertices.row(mesh.triangles(f, (k + 1) % 3));
      if (!where(0.5 * (a + b))) continue;
      sum += (b - a).norm();
      ++n;
    }
  return sum / n;
}

TEST(SurfaceRelaxationTest, AnEdgeLengthFieldGradesTheMesh) {
  // A sphere asked for edges 4 times shorter in its +x half than in its -x half: the relaxation
  // moves vertices into the +x half, shortening its edges, and keeps the surface valid.
  const ImplicitField field = [](const Eigen::Vector3d& p) { return p.norm() - 0.03; };
  const Box box{Eigen::Vector3d::Constant(-0.03), Eigen::Vector3d::Constant(0.03)};
  physics::TriangleMesh mesh = DecimateAndSmooth(ExtractIsosurface(field, box, 0.001), {.target_vertices = 400});
  OrientOutward(mesh, field);
  const auto positive = [](const Eigen::Vector3d& m) { return m.x() > 0.01; };
  const auto negative = [](const Eigen::Vector3d& m) { return m.x() < -0.01; };
  const double ratio_before = MeanEdgeLength(mesh, positive) / MeanEdgeLength(mesh, negative);
  const ImplicitField edge_length = [](const Eigen::Vector3d& p) { return p.x() > 0 ? 0.001 : 0.004; };

  RelaxOntoField(mesh, field, 30, edge_length);
  OrientOutward(mesh, field);
  EXPECT_NO_THROW(physics::ValidateTriangleMesh(mesh, "graded", physics::SurfaceRequirement::kClosed));
  for (int i = 0; i < mesh.num_vertices(); ++i) EXPECT_NEAR(field(mesh.vertices.row(i)), 0.0, 1e-9);
  const double ratio_after = MeanEdgeLength(mesh, positive) / MeanEdgeLength(mesh, negative);
  std::printf("mean edge +x / -x: %.2f before, %.2f after grading\n", ratio_before, ratio_after);
  EXPECT_NEAR(ratio_before, 1.0, 0.15) << "uniform before";
  EXPECT_LT(ratio_after, 0.8) << "shorter edges where the field asks for them";
}

}  // namespace
}  // namespace vesica::app::anatomy
