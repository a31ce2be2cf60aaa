#include "physics/mesh/barycentric.h"

#include <gtest/gtest.h>

#include "physics/mesh/primitives.h"

namespace vesica::physics {
namespace {

TEST(BarycentricTest, TriangleWeightsReproduceThePointAndProjectOffPlanePoints) {
  const Eigen::Vector3d a(0, 0, 0), b(2, 0, 0), c(0, 3, 0);
  const Eigen::Vector3d w = TriangleBarycentric({0.5, 0.6, 0.7}, a, b, c);
  EXPECT_NEAR(w.sum(), 1.0, 1e-15);
  const Eigen::Vector3d projected = w[0] * a + w[1] * b + w[2] * c;
  EXPECT_TRUE(projected.isApprox(Eigen::Vector3d(0.5, 0.6, 0.0), 1e-14));
}

TEST(BarycentricTest, ClosestPointOnTriangleCoversEveryVoronoiRegion) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  struct Case { Eigen::Vector3d p, expected; };
  const Case cases[] = {{{-1, -1, 1}, a},          {{2, -0.5, 0}, b},        {{-0.2, 3, -1}, c},
                        {{0.5, -1, 0.3}, {0.5, 0, 0}}, {{-1, 0.4, 0}, {0, 0.4, 0}}, {{1, 1, 2}, {0.5, 0.5, 0}},
                        {{0.2, 0.3, 5}, {0.2, 0.3, 0}}};
  for (const auto& k : cases) {
    const auto cp = ClosestPointOnTriangle(k.p, a, b, c);
    EXPECT_TRUE(cp.point.isApprox(k.expected, 1e-14)) << k.p.transpose();
    EXPECT_TRUE((cp.weights[0] * a + cp.weights[1] * b + cp.weights[2] * c).isApprox(cp.point, 1e-14));
    EXPECT_GE(cp.weights.minCoeff(), 0.0);
  }
}

TEST(BarycentricTest, TetWeightsInsideAndOutside) {
  const Eigen::Vector3d x0(0, 0, 0), x1(1, 0, 0), x2(0, 1, 0), x3(0, 0, 1);
  const Eigen::Vector4d w = TetBarycentric({0.1, 0.2, 0.3}, x0, x1, x2, x3);
  EXPECT_TRUE(w.isApprox(Eigen::Vector4d(0.4, 0.1, 0.2, 0.3), 1e-14));
  EXPECT_LT(TetBarycentric({1, 1, 1}, x0, x1, x2, x3).minCoeff(), 0.0);
}

TEST(BarycentricTest, LocateAndInterpolateRoundTripInABox) {
  const auto box = MakeBoxTetMesh({1.0, 0.5, 0.25}, {4, 3, 2});
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0.13, 0.21, 0.07), Eigen::Vector3d(0.99, 0.01, 0.2),
                                  Eigen::Vector3d(0.5, 0.25, 0.125)}) {
    const auto loc = LocateInTetMesh(box, p);
    ASSERT_GE(loc.tet, 0);
    EXPECT_GE(loc.weights.minCoeff(), -1e-12);
    EXPECT_TRUE(Interpolate(box, loc).isApprox(p, 1e-12));
  }
  // A point just outside still interpolates exactly (extrapolating weights).
  const Eigen::Vector3d outside(1.01, 0.2, 0.1);
  EXPECT_TRUE(Interpolate(box, LocateInTetMesh(box, outside)).isApprox(outside, 1e-12));
}

}  // namespace
}  // namespace vesica::physics
