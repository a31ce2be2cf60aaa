#include "physics/bem/kelvin_solution.h"

#include <gtest/gtest.h>

#include "physics/bem/triangle_quadrature.h"
#include "physics/mesh/primitives.h"

namespace vesica::physics {
namespace {

TEST(KelvinSolutionTest, DisplacementKernelIsSymmetricAndDecaysAsOneOverR) {
  const Eigen::Vector3d r(0.3, -0.2, 0.5);
  const Eigen::Matrix3d u = KelvinDisplacement(r, 60e3, 0.4);
  EXPECT_NEAR((u - u.transpose()).norm(), 0.0, 1e-15 * u.norm());
  EXPECT_NEAR((KelvinDisplacement(2.0 * r, 60e3, 0.4) - 0.5 * u).norm(), 0.0, 1e-14 * u.norm());
  // Along the axis r = e_z: U_zz = (4 - 4nu) / (16 pi mu (1-nu) r) = 1 / (4 pi mu r).
  EXPECT_NEAR(KelvinDisplacement({0, 0, 2.0}, 60e3, 0.4)(2, 2), 1.0 / (4 * M_PI * 60e3 * 2.0), 1e-18);
}

// Equilibrium of the Kelvin traction field: the integral of T* over a closed surface is -I for an
// interior source (the point force is balanced) and 0 for an exterior one.
TEST(KelvinSolutionTest, TractionIntegratesToMinusIdentityAroundInteriorSourceAndZeroOutside) {
  const TriangleMesh sphere = MakeIcosphere(1.0, 4);
  auto integrate = [&](const Eigen::Vector3d& source) {
    Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
    for (int f = 0; f < sphere.num_triangles(); ++f) {
      const double area = TriangleArea(sphere, f);
      const Eigen::Vector3d n = TriangleNormal(sphere, f);
      for (const auto& q : TriangleGauss7()) {
        Eigen::Vector3d x = Eigen::Vector3d::Zero();
        for (int c = 0; c < 3; ++c) x += q.barycentric[c] * sphere.vertices.row(sphere.triangles(f, c)).transpose();
        sum += q.weight * area * KelvinTraction(x - source, n, 0.4);
      }
    }
    return sum;
  };
  EXPECT_NEAR((integrate({0.1, -0.2, 0.3}) + Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-3);
  EXPECT_NEAR(integrate({2.0, 0.5, -0.3}).norm(), 0.0, 1e-3);
}

}  // namespace
}  // namespace vesica::physics
