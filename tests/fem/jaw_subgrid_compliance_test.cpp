#include "physics/fem/jaw_subgrid_compliance.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>

#include "physics/fem/fem_error.h"
#include "physics/mesh/primitives.h"

namespace vesica::physics {
namespace {

// A 60 x 60 x 30 mm slab of soft tissue (the gallbladder's 2.3 kPa, nu 0.45) and a 10 x 5 mm jaw
// at the centre of its top face, long side along x: the geometry is mirror-symmetric in x and y
// about the jaw's centre (the Kuhn tets are not, so only to the mesh's own asymmetry).
constexpr double kSize = 0.06, kDepth = 0.03;
const ElasticMaterial kTissue{2300.0, 0.45, 1000.0};

struct Slab {
  TetrahedralMesh mesh;
  TetBoundary boundary;
};

Slab MakeSlab(int cells_per_side) {
  Slab s;
  s.mesh = MakeBoxTetMesh({kSize, kSize, kDepth}, {cells_per_side, cells_per_side, cells_per_side / 2});
  s.boundary = ExtractBoundary(s.mesh);
  return s;
}

RectangularFootprint JawOnTop() {
  RectangularFootprint jaw;
  jaw.centre_m = {0.5 * kSize, 0.5 * kSize, kDepth};
  jaw.normal = Eigen::Vector3d::UnitZ();
  jaw.long_axis = Eigen::Vector3d::UnitX();
  return jaw;
}

JawSubgridCompliance Compute(const Slab& s, double radius_m) {
  JawSubgridSettings settings;
  settings.patch_radius_m = radius_m;
  return ComputeJawSubgridCompliance(s.mesh, s.boundary, kTissue, JawOnTop(), settings);
}

// The rows are the footprint's mean; the compliances are symmetric, the linear and 10-node ones
// positive definite, and the subgrid one positive semi-definite; the 10-node tets are softer than
// the linear ones in every direction (the linear tets lock under a jaw two elements wide).
TEST(JawSubgridComplianceTest, CompliancesAreSymmetricAndTheSubgridPositive) {
  const JawSubgridCompliance c = Compute(MakeSlab(12), 0.015);  // 5 mm cells
  double sum = 0;
  for (double w : c.weights) sum += w;
  EXPECT_NEAR(sum, 1.0, 1e-12);
  ASSERT_EQ(c.nodes.size(), c.weights.size());
  for (const Eigen::Matrix3d* m : {&c.linear_m_per_N, &c.quadratic_m_per_N, &c.subgrid_m_per_N})
    EXPECT_LT((*m - m->transpose()).norm(), 1e-12 * m->norm());
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(c.linear_m_per_N).eigenvalues().minCoeff(), 0.0);
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(c.quadratic_m_per_N).eigenvalues().minCoeff(), 0.0);
  EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(c.subgrid_m_per_N).eigenvalues().minCoeff(), -1e-18);
  for (int a = 0; a < 3; ++a) EXPECT_GT(c.quadratic_m_per_N(a, a), c.linear_m_per_N(a, a)) << a;
  EXPECT_GT(c.subgrid_normal_m_per_N, 0.0);
  EXPECT_NEAR(c.subgrid_normal_m_per_N, c.quadratic_normal_m_per_N - c.linear_normal_m_per_N, 1e-15);
  // Pressing with the tangential components free is softer than pulling with them held.
  EXPECT_GT(c.quadratic_normal_m_per_N, c.quadratic_m_per_N(2, 2) - 1e-15);
}

// The subgrid compliance is what the linear tets miss: it shrinks as the mesh refines (the linear
// tets converge to the continuum, the 10-node tets are already near it and move less).
TEST(JawSubgridComplianceTest, ShrinksAsTheMeshRefines) {
  const JawSubgridCompliance coarse = Compute(MakeSlab(12), 0.015);  // 5 mm
  const JawSubgridCompliance fine = Compute(MakeSlab(24), 0.015);    // 2.5 mm
  const double rel_coarse = coarse.subgrid_normal_m_per_N / coarse.quadratic_normal_m_per_N;
  const double rel_fine = fine.subgrid_normal_m_per_N / fine.quadratic_normal_m_per_N;
  EXPECT_LT(rel_fine, 0.7 * rel_coarse) << rel_coarse << " " << rel_fine;
  const double pull_coarse = coarse.subgrid_m_per_N(2, 2) / coarse.quadratic_m_per_N(2, 2);
  const double pull_fine = fine.subgrid_m_per_N(2, 2) / fine.quadratic_m_per_N(2, 2);
  EXPECT_LT(pull_fine, 0.7 * pull_coarse) << pull_coarse << " " << pull_fine;
}

// The held cut cancels in the difference: the subgrid compliance settles as the patch grows,
// while each patch's own compliance still moves with its radius.
TEST(JawSubgridComplianceTest, SettlesAsThePatchGrows) {
  const Slab slab = MakeSlab(12);
  const JawSubgridCompliance r12 = Compute(slab, 0.012), r18 = Compute(slab, 0.018), r24 = Compute(slab, 0.024);
  const double own_change =
      std::abs(r24.quadratic_normal_m_per_N - r18.quadratic_normal_m_per_N) / r24.quadratic_normal_m_per_N;
  const double subgrid_change =
      std::abs(r24.subgrid_normal_m_per_N - r18.subgrid_normal_m_per_N) / r24.subgrid_normal_m_per_N;
  EXPECT_GT(own_change, 0.05);
  EXPECT_LT(subgrid_change, 0.05);
  EXPECT_LT(std::abs(r24.subgrid_normal_m_per_N - r18.subgrid_normal_m_per_N),
            std::abs(r18.subgrid_normal_m_per_N - r12.subgrid_normal_m_per_N) + 1e-12);
  EXPECT_GT(r24.patch_tets, r18.patch_tets);
}

TEST(JawSubgridComplianceTest, RefusesBadSettingsAndPatchesByName) {
  const Slab slab = MakeSlab(12);
  JawSubgridSettings bad;
  bad.patch_radius_m = 0.0;
  EXPECT_THROW(ComputeJawSubgridCompliance(slab.mesh, slab.boundary, kTissue, JawOnTop(), bad), std::invalid_argument);
  bad.patch_radius_m = std::nan("");
  EXPECT_THROW(ComputeJawSubgridCompliance(slab.mesh, slab.boundary, kTissue, JawOnTop(), bad), std::invalid_argument);
  bad = {};
  bad.cells_along = 0;
  EXPECT_THROW(ComputeJawSubgridCompliance(slab.mesh, slab.boundary, kTissue, JawOnTop(), bad), std::invalid_argument);
  // A patch the size of the whole slab has nothing to hold.
  try {
    Compute(slab, 1.0);
    FAIL() << "expected FemError";
  } catch (const FemError& e) {
    EXPECT_NE(std::string(e.what()).find("whole body"), std::string::npos) << e.what();
  }
  // A patch smaller than the jaw's footprint.
  try {
    Compute(slab, 0.002);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("does not cover"), std::string::npos) << e.what();
  }
  // A jaw off the body.
  RectangularFootprint away = JawOnTop();
  away.centre_m.z() += 0.05;
  EXPECT_THROW(ComputeJawSubgridCompliance(slab.mesh, slab.boundary, kTissue, away), std::invalid_argument);
}

}  // namespace
}  // namespace vesica::physics
