#include "physics/mesh/mesh_quality.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "physics/mesh/primitives.h"

namespace vesica::physics {
namespace {

TEST(MeshQualityTest, RegularTetHasKnownAngleAndRatio) {
  TetrahedralMesh m;
  m.vertices.resize(4, 3);
  m.vertices << 1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1;
  m.tets.resize(1, 4);
  m.tets << 0, 1, 2, 3;
  if (SignedTetVolume(m, 0) < 0) std::swap(m.tets(0, 2), m.tets(0, 3));
  EXPECT_NEAR(MinDihedralAngleDeg(m, 0), std::acos(1.0 / 3.0) * 180.0 / std::numbers::pi, 1e-10);
  EXPECT_NEAR(RadiusEdgeRatio(m, 0), std::sqrt(6.0) / 4.0, 1e-12);
}

TEST(MeshQualityTest, KuhnBoxTetsHaveRightAngleCornersAnd45DegreeMinimum) {
  // Each Kuhn tet of a cube has dihedral angles 45, 60 and 90 degrees and R/l = sqrt(3)/2.
  const auto s = MeasureTetQuality(MakeBoxTetMesh({1, 1, 1}, {2, 2, 2}));
  EXPECT_NEAR(s.min_dihedral_deg, 45.0, 1e-9);
  EXPECT_NEAR(s.max_dihedral_deg, 90.0, 1e-9);
  EXPECT_NEAR(s.max_radius_edge, std::sqrt(3.0) / 2.0, 1e-12);
}

TEST(MeshQualityTest, SliverIsDetected) {
  TetrahedralMesh m;
  m.vertices.resize(4, 3);
  m.vertices << 0, 0, 0, 1, 0, 0, 1, 1, 0.01, 0, 1, 0;  // nearly flat square
  m.tets.resize(1, 4);
  m.tets << 0, 1, 2, 3;
  if (SignedTetVolume(m, 0) < 0) std::swap(m.tets(0, 2), m.tets(0, 3));
  EXPECT_LT(MinDihedralAngleDeg(m, 0), 2.0);
}

}  // namespace
}  // namespace vesica::physics
