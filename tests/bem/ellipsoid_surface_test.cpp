#include "physics/bem/ellipsoid_surface.h"

#include <gtest/gtest.h>

#include <numbers>

#include "physics/mesh/mesh_validation.h"

namespace vesica::physics {
namespace {

TEST(EllipsoidSurfaceTest, ExactVertexCountClosedOutwardAndOnTheEllipsoid) {
  const Eigen::Vector3d axes(0.10, 0.07, 0.04);
  for (int n : {8, 95, 296, 752, 1500, 3000}) {
    const TriangleMesh mesh = MakeEllipsoidSurface(axes, n);
    EXPECT_EQ(mesh.num_vertices(), n);
    EXPECT_EQ(mesh.num_triangles(), 2 * n - 4);  // Euler: closed genus-0 triangulation
    EXPECT_NO_THROW(ValidateTriangleMesh(mesh, "ellipsoid " + std::to_string(n), SurfaceRequirement::kClosed));
    for (int i = 0; i < n; ++i)
      EXPECT_NEAR(mesh.vertices.row(i).transpose().cwiseQuotient(axes).norm(), 1.0, 1e-12);
  }
  // Inscribed polyhedron: volume approaches 4/3 pi abc from below.
  const double exact = 4.0 / 3.0 * std::numbers::pi * axes.prod();
  const double v = EnclosedVolume(MakeEllipsoidSurface(axes, 3000));
  EXPECT_LT(v, exact);
  EXPECT_GT(v, 0.99 * exact);
}

}  // namespace
}  // namespace vesica::physics
