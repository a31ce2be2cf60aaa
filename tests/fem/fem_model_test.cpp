#include "physics/fem/fem_model.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <limits>
#include <string>

#include "physics/fem/elastic_forces.h"
#include "physics/fem/fem_error.h"
#include "tests/fem/fem_test_support.h"

namespace vesica::physics {
namespace {

FemModel UnitBlock(MassModel mass) {
  FemSettings s;
  s.mass_model = mass;
  s.material.density_kg_per_m3 = 1070.0;
  return BuildFemModel(MakeBoxTetMesh({0.02, 0.03, 0.04}, {2, 3, 2}), s, {});
}

Eigen::MatrixXd Dense(const FemModel& m, const Eigen::VectorXd& values) {
  return Eigen::MatrixXd(PatternMatrix(m.pattern, values));
}

// What BuildFemModel throws for this mesh and these settings (the FEM's own error type, not the
// mesh module's), or "no error".
std::string BuildError(const TetrahedralMesh& mesh, const FemSettings& s) {
  try {
    BuildFemModel(mesh, s, {});
  } catch (const FemError& e) {
    return e.what();
  }
  return "no error";
}

TEST(FemModelTest, StiffnessIsSymmetricWithRigidModesInItsNullSpace) {
  const FemModel m = UnitBlock(MassModel::kLumped);
  const Eigen::MatrixXd k = Dense(m, m.linear_stiffness_values);
  const double scale = k.cwiseAbs().maxCoeff();
  EXPECT_LT((k - k.transpose()).cwiseAbs().maxCoeff(), 1e-12 * scale);
  for (int w = 0; w < 3; ++w) {
    Eigen::VectorXd translation(m.num_dofs()), rotation(m.num_dofs());
    for (int i = 0; i < m.num_nodes(); ++i) {
      translation.segment<3>(3 * i) = Eigen::Vector3d::Unit(w);
      rotation.segment<3>(3 * i) = Eigen::Vector3d::Unit(w).cross(Eigen::Vector3d(m.rest_mesh.vertices.row(i)));
    }
    EXPECT_LT((k * translation).cwiseAbs().maxCoeff(), 1e-10 * scale);
    EXPECT_LT((k * rotation).cwiseAbs().maxCoeff(), 1e-10 * scale * 0.04);
  }
  // Positive semi-definite with exactly six zero modes.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(k);
  EXPECT_GT(eig.eigenvalues()[6], 1e-6 * scale);
  EXPECT_LT(std::abs(eig.eigenvalues()[5]), 1e-9 * scale);
}

TEST(FemModelTest, LumpedAndConsistentMassBothSumToTheBodyMass) {
  const double mass = 1070.0 * 0.02 * 0.03 * 0.04;
  const FemModel lumped = UnitBlock(MassModel::kLumped);
  const FemModel consistent = UnitBlock(MassModel::kConsistent);
  EXPECT_NEAR(lumped.lumped_mass_kg.sum(), 3.0 * mass, 1e-14);
  // 1^T M 1 per axis is the total mass for a consistent matrix too.
  const Eigen::VectorXd ones_x = Eigen::Vector3d::UnitX().replicate(consistent.num_nodes(), 1);
  EXPECT_NEAR(ones_x.dot(consistent.MassTimes(ones_x)), mass, 1e-14);
  const Eigen::MatrixXd mc = Dense(consistent, consistent.consistent_mass_values);
  EXPECT_LT((mc - mc.transpose()).cwiseAbs().maxCoeff(), 1e-18);
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(mc).eigenvalues()[0], 0.0);
  const Eigen::Vector3d g(0, 0, -9.81);
  EXPECT_NEAR(consistent.GravityForces(g).sum(), -9.81 * mass, 1e-13);
}

// The consistent matrix of one linear tet, entry by entry: rho V / 20 (1 + delta_ab) on each axis,
// nothing across axes (a lumped matrix in the consistent slots would fail the off-diagonals).
TEST(FemModelTest, ConsistentMassOfOneTetIsRhoVOverTwentyTimesOnePlusDelta) {
  TetrahedralMesh tet;
  tet.vertices.resize(4, 3);
  tet.vertices << 0, 0, 0, 0.02, 0, 0, 0.003, 0.025, 0, 0.004, 0.006, 0.03;
  tet.tets.resize(1, 4);
  tet.tets << 0, 1, 2, 3;
  FemSettings s;
  s.mass_model = MassModel::kConsistent;
  s.material.density_kg_per_m3 = 1070.0;
  const FemModel m = BuildFemModel(tet, s, {});
  const double volume = 0.02 * 0.025 * 0.03 / 6.0;  // base triangle (z = 0) x height / 3
  const double rho_v = 1070.0 * volume;
  const Eigen::MatrixXd mc = Dense(m, m.consistent_mass_values);
  ASSERT_EQ(mc.rows(), 12);
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j) {
      const double expected = i % 3 != j % 3 ? 0.0 : rho_v / 20.0 * (i / 3 == j / 3 ? 2.0 : 1.0);
      EXPECT_NEAR(mc(i, j), expected, 1e-12 * rho_v) << "entry (" << i << ", " << j << ")";
    }
  EXPECT_NEAR(m.lumped_mass_kg.sum(), 3.0 * rho_v, 1e-12 * rho_v);
}

TEST(FemModelTest, BadMaterialIsAnErrorNamingBodyAndField) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({1, 1, 1}, {1, 1, 1});
  auto message = [&](const FemSettings& s) { return BuildError(mesh, s); };
  FemSettings s;
  s.body_name = "gallbladder";
  s.material.poisson_ratio = 0.5;
  EXPECT_NE(message(s).find("gallbladder: material poisson_ratio = 0.5"), std::string::npos) << message(s);
  for (double nu : {0.7, -1.0, -1.5, std::numeric_limits<double>::quiet_NaN()}) {
    s.material.poisson_ratio = nu;
    EXPECT_NE(message(s).find("gallbladder: material poisson_ratio = "), std::string::npos) << nu << message(s);
  }
  s.material.poisson_ratio = 0.45;
  s.material.youngs_modulus_Pa = 0.0;
  EXPECT_NE(message(s).find("gallbladder: material youngs_modulus_Pa = 0"), std::string::npos) << message(s);
  s.material.youngs_modulus_Pa = -3.0;
  EXPECT_NE(message(s).find("gallbladder: material youngs_modulus_Pa = -3"), std::string::npos) << message(s);
  s.material.youngs_modulus_Pa = 2300.0;
  s.time_step_s = 0.0;
  EXPECT_NE(message(s).find("time_step_s"), std::string::npos) << message(s);
  s.time_step_s = 0.01;
  s.rotated_factor_sweeps = 0;
  EXPECT_NE(message(s).find("gallbladder: setting rotated_factor_sweeps = 0"), std::string::npos) << message(s);
  s.rotated_factor_sweeps = 1;
  s.rotated_factor_local_nodes_max = -4;
  EXPECT_NE(message(s).find("gallbladder: setting rotated_factor_local_nodes_max = -4"), std::string::npos)
      << message(s);
  s.rotated_factor_local_nodes_max = 0;
  s.rotated_factor_local_share = 1.5;
  EXPECT_NE(message(s).find("gallbladder: setting rotated_factor_local_share = 1.5"), std::string::npos) << message(s);
  s.rotated_factor_local_share = 0.0;
  s.rotated_factor_adopt_steps = -1;
  EXPECT_NE(message(s).find("gallbladder: setting rotated_factor_adopt_steps = -1"), std::string::npos) << message(s);
  s.rotated_factor_adopt_steps = 15;
  s.rotated_factor_rotation_refresh_rad = -0.01;
  EXPECT_NE(message(s).find("gallbladder: setting rotated_factor_rotation_refresh_rad = -0.01"), std::string::npos)
      << message(s);
  s.rotated_factor_rotation_refresh_rad = std::numeric_limits<double>::infinity();
  EXPECT_NE(message(s).find("gallbladder: setting rotated_factor_rotation_refresh_rad = inf"), std::string::npos)
      << message(s);
}

// Settings every step would fail with are refused when the body is built, naming the setting
// (each case below stepped a 4 x 4 x 4-cell box under gravity without these checks: the Newmark
// ones diverged after 7 and 15 accepted steps, the overflowing ones failed every step).
// Newmark with 2 beta < gamma is only conditionally stable, and a tet mesh's stiffest modes are
// beyond any usable h. A step so short, or a damping so stiff, that the step's system leaves the
// range its solver computes in (float for the rotated factor, double otherwise) leaves nothing
// to solve.
TEST(FemModelTest, SettingsNoStepCouldSurviveAreErrorsNamingTheSetting) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.01, 0.01, 0.01}, {4, 4, 4});
  auto message = [&](const FemSettings& s) { return BuildError(mesh, s); };
  FemSettings s;
  s.body_name = "gallbladder";
  s.integrator = TimeIntegrator::kNewmark;
  s.newmark_beta = 1.0 / 6.0;  // the linear-acceleration method: stable only for omega h < 3.46
  EXPECT_NE(message(s).find("gallbladder: setting newmark_beta = 0.166667 is out of range (2 beta >= gamma = 0.5"),
            std::string::npos)
      << message(s);
  s.newmark_beta = 0.25;
  s.newmark_gamma = 0.6;
  EXPECT_NE(message(s).find("gallbladder: setting newmark_beta = 0.25 is out of range (2 beta >= gamma = 0.6"),
            std::string::npos)
      << message(s);
  s.newmark_beta = 0.3025;  // (gamma + 1/2)^2 / 4: numerically damped and unconditionally stable
  EXPECT_EQ(message(s), "no error");
  s.integrator = TimeIntegrator::kBackwardEuler;  // Newmark's parameters are not used
  s.newmark_beta = 1.0 / 6.0;
  EXPECT_EQ(message(s), "no error");

  s.newmark_beta = 0.25;
  s.newmark_gamma = 0.5;
  s.time_step_s = 0.005;
  for (TimeIntegrator integrator : {TimeIntegrator::kBackwardEuler, TimeIntegrator::kNewmark}) {
    s.integrator = integrator;
    for (LinearSolverKind solver : {LinearSolverKind::kCholmod, LinearSolverKind::kRotatedFactorPcg}) {
      s.solver = solver;
      const bool float_arrays = solver == LinearSolverKind::kRotatedFactorPcg;
      s.time_step_s = 1e-300;  // M / h^2 is infinite
      EXPECT_NE(message(s).find("gallbladder: setting time_step_s = 1e-300 makes the step's system overflow"),
                std::string::npos)
          << message(s);
      s.time_step_s = 1e-19;  // entries up to 6e33: these steps still succeed, in float too
      EXPECT_EQ(message(s), "no error");
      s.time_step_s = 1e308;  // M / h^2 underflows: backward Euler becomes statics, which the fixed nodes allow
      EXPECT_EQ(message(s), "no error");
      s.time_step_s = 0.005;
      s.rayleigh_stiffness_s = 1e40;  // entries up to 2e44: beyond float, within double
      if (float_arrays)
        EXPECT_NE(message(s).find("gallbladder: setting rayleigh_stiffness_s = 1e+40 makes the step's system overflow"),
                  std::string::npos)
            << message(s);
      else
        EXPECT_EQ(message(s), "no error");
      if (float_arrays) {  // the same solver told to keep everything in double takes the double range
        s.rotated_factor_single_precision = false;
        s.rotated_factor_float_sweeps = false;
        s.rotated_factor_gauss_seidel = true;
        EXPECT_EQ(message(s), "no error");
        s.rotated_factor_float_sweeps = true;
        EXPECT_NE(message(s).find("rayleigh_stiffness_s = 1e+40 makes the step's system overflow"), std::string::npos)
            << message(s);
        s.rotated_factor_single_precision = true;
        s.rotated_factor_gauss_seidel = false;
      }
      s.rayleigh_stiffness_s = 0.1;
      s.rayleigh_mass_per_s = 1e300;  // entries up to 6e297: |b|^2 overflows
      EXPECT_NE(message(s).find("gallbladder: setting rayleigh_mass_per_s = 1e+300 makes the step's system overflow"),
                std::string::npos)
          << message(s);
      s.rayleigh_mass_per_s = 0.1;
      EXPECT_EQ(message(s), "no error");
    }
  }
}

TEST(FemModelTest, InvertedAndDegenerateTetsAreErrorsNamingBodyAndTet) {
  auto message = [](const TetrahedralMesh& mesh) {
    FemSettings s;
    s.body_name = "gallbladder";
    return BuildError(mesh, s);
  };
  TetrahedralMesh inverted = MakeBoxTetMesh({1, 1, 1}, {2, 1, 1});
  std::swap(inverted.tets(4, 1), inverted.tets(4, 2));  // tet 4 alone now has negative volume
  EXPECT_NE(message(inverted).find("gallbladder: tetrahedron 4: is inverted"), std::string::npos) << message(inverted);
  // One tet collapsed onto a plane (its fourth vertex moved into the plane of the other three),
  // the others intact: the message names that tet.
  const int t = 7;
  TetrahedralMesh collapsed = MakeBoxTetMesh({1, 1, 1}, {2, 1, 1});
  collapsed.vertices.conservativeResize(collapsed.num_vertices() + 1, 3);
  const Eigen::Vector3d a = collapsed.vertices.row(collapsed.tets(t, 0)),
                        b = collapsed.vertices.row(collapsed.tets(t, 1)),
                        c = collapsed.vertices.row(collapsed.tets(t, 2));
  collapsed.vertices.row(collapsed.num_vertices() - 1) = ((a + b + c) / 3.0).transpose();
  collapsed.tets(t, 3) = collapsed.num_vertices() - 1;
  EXPECT_NE(message(collapsed).find("gallbladder: tetrahedron 7: is degenerate"), std::string::npos)
      << message(collapsed);
}

// A vertex no tet uses has no mass and no stiffness: a singular system unless it is held.
TEST(FemModelTest, VertexInNoTetIsAnErrorUnlessItIsHeld) {
  TetrahedralMesh mesh = MakeBoxTetMesh({1, 1, 1}, {1, 1, 1});
  mesh.vertices.conservativeResize(9, 3);
  mesh.vertices.row(8) << 2.0, 2.0, 2.0;
  FemSettings s;
  s.body_name = "gallbladder";
  try {
    BuildFemModel(mesh, s, {{8, {true, true, false}}});
    FAIL() << "expected FemError";
  } catch (const FemError& e) {
    EXPECT_NE(std::string(e.what()).find("gallbladder: vertex 8 belongs to no tetrahedron and is not fixed"),
              std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(BuildFemModel(mesh, s, {{8, {true, true, true}}}));
}

TEST(FemModelTest, FixedNodeOutOfRangeIsAnError) {
  FemSettings s;
  s.body_name = "gallbladder";
  try {
    BuildFemModel(MakeBoxTetMesh({1, 1, 1}, {1, 1, 1}), s, {{8, {true, true, true}}});
    FAIL() << "expected FemError";
  } catch (const FemError& e) {
    EXPECT_NE(std::string(e.what()).find("gallbladder: fixed node 8"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vesica::physics
