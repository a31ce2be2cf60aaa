// The registration result replayed as a motion (physics/registration/displacement_series.h), the
// source the breathing patient's liver can follow instead of ChainMail.

#include "physics/registration/displacement_series.h"

#include <gtest/gtest.h>

#include "physics/mesh/primitives.h"

namespace vesica::physics {
namespace {

// u(X, t) = (a + G X) s(t): linear in X, so barycentric sampling is exact.
Vertices Field(const TetrahedralMesh& mesh, double scale) {
  Vertices u(mesh.vertices.rows(), 3);
  for (Eigen::Index i = 0; i < u.rows(); ++i) {
    const Eigen::Vector3d X = mesh.vertices.row(i).transpose();
    u.row(i) = (scale * (Eigen::Vector3d(0.0, 0.002, -0.010) + 0.1 * Eigen::Vector3d(X.y(), 0.0, X.x()))).transpose();
  }
  return u;
}

TEST(DisplacementSeriesTest, InterpolatesInSpaceAndTimeAndRepeats) {
  const TetrahedralMesh mesh = MakeBoxTetMesh(Eigen::Vector3d(0.1, 0.08, 0.06), Eigen::Vector3i(4, 3, 2));
  // Three frames 0.5 s apart: scale 0, 1, 0.5; period 1.5 s.
  DisplacementSeries series(mesh, {{0.0, Field(mesh, 0.0)}, {0.5, Field(mesh, 1.0)}, {1.0, Field(mesh, 0.5)}});
  EXPECT_DOUBLE_EQ(series.period_s(), 1.5);
  const Eigen::Vector3d p(0.031, 0.047, 0.022);
  const auto bound = series.Bind({p});
  auto expected = [&](double scale) {
    return (scale * (Eigen::Vector3d(0.0, 0.002, -0.010) + 0.1 * Eigen::Vector3d(p.y(), 0.0, p.x()))).eval();
  };
  EXPECT_TRUE(series.Sample(bound, 0.5)[0].isApprox(expected(1.0), 1e-12));
  EXPECT_TRUE(series.Sample(bound, 0.25)[0].isApprox(expected(0.5), 1e-12));
  EXPECT_TRUE(series.Sample(bound, 0.75)[0].isApprox(expected(0.75), 1e-12));
  EXPECT_TRUE(series.Sample(bound, 1.25)[0].isApprox(expected(0.25), 1e-12));  // back towards frame 0
  EXPECT_TRUE(series.Sample(bound, 0.25 + 3 * 1.5)[0].isApprox(expected(0.5), 1e-12));
  EXPECT_TRUE(series.Sample(bound, 0.25 - 1.5)[0].isApprox(expected(0.5), 1e-12));
}

TEST(DisplacementSeriesTest, RefusesBadFrames) {
  const TetrahedralMesh mesh = MakeBoxTetMesh(Eigen::Vector3d(0.1, 0.08, 0.06), Eigen::Vector3i(2, 2, 2));
  EXPECT_THROW(DisplacementSeries(mesh, {}), std::invalid_argument);
  EXPECT_THROW(DisplacementSeries(mesh, {{0.0, Vertices::Zero(3, 3)}}), std::invalid_argument);
  EXPECT_THROW(DisplacementSeries(mesh, {{0.0, Field(mesh, 1)}, {0.0, Field(mesh, 1)}}), std::invalid_argument);
  Vertices nan = Field(mesh, 1);
  nan(2, 1) = std::nan("");
  EXPECT_THROW(DisplacementSeries(mesh, {{0.0, nan}}), std::invalid_argument);
}

}  // namespace
}  // namespace vesica::physics
