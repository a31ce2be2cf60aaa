#include "physics/fem/linear_statics.h"

#include <gtest/gtest.h>

#include <cmath>

#include "physics/fem/fem_error.h"
#include "tests/fem/fem_test_support.h"

namespace vesica::physics {
namespace {

using testing::Clamp;
using testing::NodesOnPlane;

// Uniaxial stress sigma along z on a block held only on three symmetry planes: linear tets must
// reproduce u = (sigma/E)(-nu x, -nu y, z) exactly (the patch test), on a regular grid and on one
// whose interior nodes are moved off it (a constant strain is exact on any tet mesh).
TEST(LinearStaticsTest, PatchTestReproducesUniaxialStress) {
  for (bool jittered : {false, true}) {
    SCOPED_TRACE(jittered ? "jittered mesh" : "regular mesh");
    const Eigen::Vector3d size(2.0, 1.5, 3.0);
    TetrahedralMesh mesh = MakeBoxTetMesh(size, {3, 2, 4});
    if (jittered) {
      // Interior nodes only (the loaded face and the symmetry planes stay planar), by up to 0.2 of
      // a cell (0.67 x 0.75 x 0.75) along each axis, a fixed pseudo-random pattern.
      for (int i = 0; i < mesh.num_vertices(); ++i) {
        const Eigen::Vector3d x = mesh.vertices.row(i);
        if ((x.array() < 1e-12).any() || ((size - x).array() < 1e-12).any()) continue;
        const Eigen::Vector3d jitter(std::sin(12.9898 * i), std::sin(78.233 * i + 1.0), std::sin(37.719 * i + 2.0));
        mesh.vertices.row(i) += (0.13 * jitter).transpose();
      }
    }
    FemSettings s;
    s.body_name = "patch block";
    s.material.youngs_modulus_Pa = 5000.0;
    s.material.poisson_ratio = 0.3;
    std::vector<DirichletNode> fixed;
    for (int i = 0; i < mesh.num_vertices(); ++i) {
      DirichletNode d{i, {false, false, false}};
      for (int axis = 0; axis < 3; ++axis) d.axes[axis] = std::abs(mesh.vertices(i, axis)) < 1e-12;
      if (d.axes[0] || d.axes[1] || d.axes[2]) fixed.push_back(d);
    }
    const FemModel model = BuildFemModel(mesh, s, fixed);
    const double sigma = 7.0;
    const Eigen::VectorXd f = testing::PlaneTractionForces(mesh, 2, 3.0, {0.0, 0.0, sigma});
    const Eigen::VectorXd u = SolveLinearStatics(model, f);
    const double e = 5000.0, nu = 0.3;
    double max_error = 0.0, max_u = 0.0, max_moved = 0.0;
    for (int i = 0; i < mesh.num_vertices(); ++i) {
      const Eigen::Vector3d x = mesh.vertices.row(i);
      const Eigen::Vector3d exact = sigma / e * Eigen::Vector3d(-nu * x.x(), -nu * x.y(), x.z());
      max_error = std::max(max_error, (u.segment<3>(3 * i) - exact).cwiseAbs().maxCoeff());
      max_u = std::max(max_u, exact.cwiseAbs().maxCoeff());
      const Eigen::Vector3d grid =
          (x.array() / Eigen::Array3d(2.0 / 3, 0.75, 0.75)).round() * Eigen::Array3d(2.0 / 3, 0.75, 0.75);
      max_moved = std::max(max_moved, (x - grid).cwiseAbs().maxCoeff());
    }
    EXPECT_LT(max_error, 1e-9 * max_u);
    EXPECT_NEAR(max_u, sigma / e * 3.0, 1e-15);
    if (jittered) {
      EXPECT_GT(max_moved, 0.1);  // the mesh really left the grid
    }
  }
}

// Prescribed displacement: stretching the block by moving the top face gives the same field.
TEST(LinearStaticsTest, PrescribedDisplacementGivesUniformStrain) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({1.0, 1.0, 2.0}, {2, 2, 4});
  FemSettings s;
  s.material.poisson_ratio = 0.25;
  std::vector<DirichletNode> fixed;
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    DirichletNode d{i, {false, false, false}};
    for (int axis = 0; axis < 2; ++axis) d.axes[axis] = std::abs(mesh.vertices(i, axis)) < 1e-12;
    d.axes[2] = std::abs(mesh.vertices(i, 2)) < 1e-12 || std::abs(mesh.vertices(i, 2) - 2.0) < 1e-12;
    if (d.axes[0] || d.axes[1] || d.axes[2]) fixed.push_back(d);
  }
  const FemModel model = BuildFemModel(mesh, s, fixed);
  Eigen::VectorXd prescribed = Eigen::VectorXd::Zero(model.num_dofs());
  const double strain = 1e-3;
  for (int i = 0; i < mesh.num_vertices(); ++i) prescribed[3 * i + 2] = strain * mesh.vertices(i, 2);
  const Eigen::VectorXd u = SolveLinearStatics(model, Eigen::VectorXd::Zero(model.num_dofs()), prescribed);
  for (int i = 0; i < mesh.num_vertices(); ++i) {
    EXPECT_NEAR(u[3 * i + 0], -0.25 * strain * mesh.vertices(i, 0), 1e-12);
    EXPECT_NEAR(u[3 * i + 1], -0.25 * strain * mesh.vertices(i, 1), 1e-12);
    EXPECT_NEAR(u[3 * i + 2], strain * mesh.vertices(i, 2), 1e-12);
  }
}

// Cantilever L = 10, b = h = 1, E = 1000, nu = 0.3, tip load P = 1: Euler-Bernoulli gives
// PL^3/(3EI) = 4.0. Linear tets are stiff in bending; the deflection must rise toward 4.0 as the
// mesh refines and reach 0.85 * 4.0 with 6 elements through the thickness.
TEST(LinearStaticsTest, CantileverTipDeflectionConvergesTowardBeamTheory) {
  std::vector<double> tip;
  for (int c : {2, 4, 6}) {
    FemSettings s;
    s.body_name = "cantilever";
    const FemModel model = testing::MakeCantilever(c, s);
    const auto& mesh = model.rest_mesh;
    // P = 1 spread as a uniform shear traction over the 1 x 1 end face.
    const Eigen::VectorXd f = testing::PlaneTractionForces(mesh, 0, 10.0, {0.0, 0.0, -1.0});
    EXPECT_NEAR(f.sum(), -1.0, 1e-12);
    const Eigen::VectorXd u = SolveLinearStatics(model, f);
    tip.push_back(-testing::MeanDisplacement(u, NodesOnPlane(mesh, 0, 10.0), 2));
    std::printf("cantilever %d cells through thickness: tip deflection %.4f (beam theory 4.0)\n", c, tip.back());
  }
  EXPECT_LT(tip[0], tip[1]);
  EXPECT_LT(tip[1], tip[2]);
  EXPECT_GE(tip[2], 0.85 * 4.0);
  EXPECT_LT(tip[2], 4.2);  // beam theory plus shear (~0.03) and clamping effects bound it
}

TEST(LinearStaticsTest, NoFixedNodesIsAnErrorNamingTheBody) {
  FemSettings s;
  s.body_name = "loose gallbladder";
  const FemModel model = BuildFemModel(MakeBoxTetMesh({1, 1, 1}, {1, 1, 1}), s, {});
  try {
    SolveLinearStatics(model, Eigen::VectorXd::Zero(model.num_dofs()));
    FAIL() << "expected FemError";
  } catch (const FemError& e) {
    EXPECT_NE(std::string(e.what()).find("loose gallbladder"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("fixed nodes"), std::string::npos);
  }
}

TEST(LinearStaticsTest, FixedNodesLeavingARigidMotionAreRejected) {
  FemSettings s;
  s.body_name = "hinged block";
  const TetrahedralMesh mesh = MakeBoxTetMesh({1, 1, 1}, {2, 2, 2});
  // Two clamped nodes leave the rotation about the line through them free.
  const FemModel model = BuildFemModel(mesh, s, testing::Clamp({0, 26}));
  EXPECT_THROW(SolveLinearStatics(model, Eigen::VectorXd::Ones(model.num_dofs())), FemError);
}

TEST(LinearStaticsTest, WrongSizedForceIsRejected) {
  FemSettings s;
  const TetrahedralMesh mesh = MakeBoxTetMesh({1, 1, 1}, {1, 1, 1});
  const FemModel model = BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 2, 0.0)));
  EXPECT_THROW(SolveLinearStatics(model, Eigen::VectorXd::Zero(5)), FemError);
}

}  // namespace
}  // namespace vesica::physics
