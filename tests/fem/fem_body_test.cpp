#include "physics/fem/fem_body.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <limits>

#include "physics/fem/elastic_forces.h"
#include "physics/fem/fem_error.h"
#include "physics/fem/linear_statics.h"
#include "tests/fem/fem_test_support.h"

namespace vesica::physics {
namespace {

using testing::Clamp;
using testing::GallbladderNewmarkSettings;
using testing::NodesOnPlane;

// A small clamped block whose modes are computed densely (the reference for the integrators).
struct ModalBlock {
  std::shared_ptr<const FemModel> model;
  double omega = 0.0;    // first natural frequency, rad/s
  Eigen::VectorXd mode;  // 3n, M-normalised, zero at fixed dofs
};

ModalBlock MakeModalBlock(TimeIntegrator integrator, double steps_per_period) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.06, 0.02, 0.02}, {6, 2, 2});
  FemSettings s;
  s.body_name = "modal block";
  s.element_model = ElementModel::kLinear;
  s.integrator = integrator;
  s.material = {2300.0, 0.45, 1000.0};
  auto probe = std::make_shared<FemModel>(BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 0, 0.0))));
  std::vector<int> free;
  for (int i = 0; i < probe->num_dofs(); ++i)
    if (probe->free_dofs[i] == 1.0) free.push_back(i);
  const Eigen::MatrixXd k_full(PatternMatrix(probe->pattern, probe->linear_stiffness_values));
  const int nf = static_cast<int>(free.size());
  Eigen::MatrixXd k(nf, nf);
  Eigen::VectorXd m(nf);
  for (int a = 0; a < nf; ++a) {
    m[a] = probe->lumped_mass_kg[free[a]];
    for (int b = 0; b < nf; ++b) k(a, b) = k_full(free[a], free[b]);
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(k, Eigen::MatrixXd(m.asDiagonal()));
  ModalBlock block;
  block.omega = std::sqrt(eig.eigenvalues()[0]);
  block.mode = Eigen::VectorXd::Zero(probe->num_dofs());
  for (int a = 0; a < nf; ++a) block.mode[free[a]] = eig.eigenvectors()(a, 0);  // M-normalised
  s.time_step_s = 2.0 * M_PI / block.omega / steps_per_period;
  block.model = std::make_shared<FemModel>(BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 0, 0.0))));
  return block;
}

// Modal amplitude |q + i qdot/omega| of the body's state in the block's first mode.
double ModalAmplitude(const ModalBlock& b, const FemBody& body) {
  const double q = b.mode.dot(b.model->MassTimes(body.state().displacement_m));
  const double qdot = b.mode.dot(b.model->MassTimes(body.state().velocity_m_per_s));
  return std::hypot(q, qdot / b.omega);
}

TEST(FemBodyTest, NewmarkAverageAccelerationConservesAnUndampedModeOver1000Steps) {
  const ModalBlock b = MakeModalBlock(TimeIntegrator::kNewmark, 20.0);
  FemBody body(b.model);
  const double amplitude = 1e-3;
  body.SetState(amplitude * b.mode, Eigen::VectorXd::Zero(b.model->num_dofs()));
  const double energy0 = 0.5 * b.omega * b.omega * amplitude * amplitude;
  double min_q = 0.0;
  for (int step = 0; step < 1000; ++step) {
    const StepReport r = body.Step();
    ASSERT_TRUE(r.accepted) << r.rejection_reason;
    EXPECT_NEAR(r.energy_J, energy0, 1e-9 * energy0);
    min_q = std::min(min_q, b.mode.dot(b.model->MassTimes(body.state().displacement_m)));
  }
  EXPECT_NEAR(ModalAmplitude(b, body), amplitude, 1e-9 * amplitude);
  EXPECT_NEAR(body.KineticEnergy() + body.ElasticEnergy(), energy0, 1e-9 * energy0);
  EXPECT_LT(min_q, -0.99 * amplitude);  // it really oscillated through the opposite extreme
}

TEST(FemBodyTest, BackwardEulerDampsAModeAsOneOverSqrtOnePlusOmegaHSquared) {
  const ModalBlock b = MakeModalBlock(TimeIntegrator::kBackwardEuler, 10.0);
  FemBody body(b.model);
  body.SetState(1e-3 * b.mode, Eigen::VectorXd::Zero(b.model->num_dofs()));
  const double omega_h = b.omega * b.model->settings.time_step_s;
  const double expected = 1.0 / std::sqrt(1.0 + omega_h * omega_h);
  for (int step = 0; step < 20; ++step) {
    const double before = ModalAmplitude(b, body);
    ASSERT_TRUE(body.Step().accepted);
    EXPECT_NEAR(ModalAmplitude(b, body) / before, expected, 1e-9) << "step " << step;
  }
}

// Rayleigh damping D = alpha M + beta K keeps the modes apart, so the first mode's coordinates
// follow Newmark's average-acceleration recurrence for q'' + (alpha + beta omega^2) q' + omega^2 q = 0
// step for step (the damping drive D v enters every step's right-hand side).
TEST(FemBodyTest, NewmarkWithRayleighDampingFollowsTheModalRecurrence) {
  for (LinearSolverKind solver : {LinearSolverKind::kCholmod, LinearSolverKind::kRotatedFactorPcg}) {
    ModalBlock b = MakeModalBlock(TimeIntegrator::kNewmark, 20.0);
    FemSettings s = b.model->settings;
    s.solver = solver;
    s.pcg_relative_tolerance = 1e-12;
    s.rayleigh_mass_per_s = 0.2 * b.omega;  // zeta = 0.1 + 0.05: a few per cent a step
    s.rayleigh_stiffness_s = 0.1 / b.omega;
    const TetrahedralMesh& mesh = b.model->rest_mesh;
    b.model = std::make_shared<FemModel>(BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 0, 0.0))));
    FemBody body(b.model);
    const double h = s.time_step_s, k = b.omega * b.omega;
    const double c = s.rayleigh_mass_per_s + s.rayleigh_stiffness_s * k;
    double q = 1e-3, v = 0.3 * b.omega * 1e-3, a = -(c * v + k * q);
    body.SetState(q * b.mode, v * b.mode);
    for (int step = 0; step < 60; ++step) {
      ASSERT_TRUE(body.Step().accepted);
      const double a_next =
          -(c * (v + 0.5 * h * a) + k * (q + h * v + 0.25 * h * h * a)) / (1.0 + 0.5 * c * h + 0.25 * k * h * h);
      q += h * v + 0.25 * h * h * (a + a_next);
      v += 0.5 * h * (a + a_next);
      a = a_next;
      const double body_q = b.mode.dot(b.model->MassTimes(body.state().displacement_m));
      const double body_v = b.mode.dot(b.model->MassTimes(body.state().velocity_m_per_s));
      EXPECT_NEAR(body_q, q, 1e-9 * 1e-3) << "step " << step;
      EXPECT_NEAR(body_v, v, 1e-9 * 1e-3 * b.omega) << "step " << step;
    }
    EXPECT_LT(std::hypot(q, v / b.omega), 0.1 * 1e-3);  // it really decayed (exp(-zeta omega t) = 0.06)
  }
}

// First bending frequency of the cantilever against Euler-Bernoulli,
// omega_1 = 1.8751^2 sqrt(EI / (rho A L^4)), measured from the period of the released tip.
TEST(FemBodyTest, CantileverFirstBendingFrequencyWithinThreePercentOfBeamTheory) {
  FemSettings s;
  s.body_name = "cantilever";
  s.element_model = ElementModel::kLinear;
  s.integrator = TimeIntegrator::kNewmark;
  s.material.density_kg_per_m3 = 1.0;
  const double beam_omega = 1.8751 * 1.8751 * std::sqrt(1000.0 / 12.0 / 1.0e4);
  const double period = 2.0 * M_PI / beam_omega;
  s.time_step_s = period / 200.0;
  const int cells = 8;
  auto model = std::make_shared<FemModel>(testing::MakeCantilever(cells, s));
  const std::vector<int> tip = NodesOnPlane(model->rest_mesh, 0, 10.0);
  // Release from the static deflection under a tip load (mostly the first mode).
  const Eigen::VectorXd load = testing::PlaneTractionForces(model->rest_mesh, 0, 10.0, {0, 0, -0.01});
  FemBody body(model);
  body.SetState(SolveLinearStatics(*model, load), Eigen::VectorXd::Zero(model->num_dofs()));
  std::vector<double> crossings;  // upward zero crossings of the tip, s
  double previous = testing::MeanDisplacement(body.state().displacement_m, tip, 2);
  for (int step = 0; step < 360 && crossings.size() < 2; ++step) {
    ASSERT_TRUE(body.Step().accepted);
    const double now = testing::MeanDisplacement(body.state().displacement_m, tip, 2);
    if ((previous < 0.0) != (now < 0.0)) {
      const double t = body.state().time_s - s.time_step_s * now / (now - previous);
      crossings.push_back(t);
    }
    previous = now;
  }
  ASSERT_EQ(crossings.size(), 2u);
  const double omega = M_PI / (crossings[1] - crossings[0]);  // half a period between crossings
  std::printf("cantilever %d cells through thickness: omega_1 %.5f rad/s, beam theory %.5f (ratio %.4f)\n", cells,
              omega, beam_omega, omega / beam_omega);
  // The issue asks for 5 %; 8 cells give 1.013 (linear tets are stiff in bending), so the bound is
  // held at 3 %: a mass or stiffness off by 6 % would move omega by 3 % and fail.
  EXPECT_NEAR(omega / beam_omega, 1.0, 0.03);
}

// A gallbladder-sized body (8 x 3 x 3 cm box: the pear-shaped .vtu mesh needs app/'s VTK reader,
// not in the physics build) pulled at one node, then released: it must come back to rest, every
// step accepted, its energy never above the work the pull did.
// The gallbladder's material, corotational, h = 5 ms, damped so that a released body comes to rest
// within a few seconds.
FemSettings DampedGallbladderSettings(LinearSolverKind solver, TimeIntegrator integrator) {
  FemSettings s;
  s.body_name = "gallbladder";
  s.element_model = ElementModel::kCorotational;
  s.integrator = integrator;
  s.solver = solver;
  s.material = {2300.0, 0.45, 1000.0};
  s.time_step_s = 0.005;
  s.rayleigh_mass_per_s = 10.0;  // 1/s: the energy decays about as exp(-10 t)
  s.rayleigh_stiffness_s = 0.01;
  s.pcg_max_iterations = 100;
  return s;
}

double PullAndRelease(LinearSolverKind solver, int refresh_steps, TimeIntegrator integrator) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {8, 3, 3});
  FemSettings s = DampedGallbladderSettings(solver, integrator);
  s.cholmod_refresh_steps = refresh_steps;
  auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 0, 0.0))));
  FemBody body(model);
  const int grasped = mesh.num_vertices() - 1;  // corner at the free end
  Eigen::VectorXd pull = Eigen::VectorXd::Zero(model->num_dofs());
  pull.segment<3>(3 * grasped) = Eigen::Vector3d(0.05, 0.0, 0.1);  // N: lifts the fundus ~cm
  body.SetExternalForces(pull);
  double work = 0.0, max_energy = 0.0, max_lift = 0.0;
  for (int step = 0; step < 600; ++step) {
    if (step == 100) body.SetExternalForces(Eigen::VectorXd::Zero(model->num_dofs()));
    const Eigen::VectorXd before = body.state().displacement_m;
    const StepReport r = body.Step();
    EXPECT_TRUE(r.accepted) << r.rejection_reason;
    work += body.state().external_force_N.dot(body.state().displacement_m - before);
    max_energy = std::max(max_energy, r.energy_J);
    max_lift = std::max(max_lift, body.state().displacement_m[3 * grasped + 2]);
    EXPECT_LE(r.energy_J, work * 1.05 + 1e-12) << "step " << step;
    // The body's own energy, not only the step's second-order estimate of it.
    EXPECT_LE(body.KineticEnergy() + body.ElasticEnergy(), work * 1.05 + 1e-12) << "step " << step;
  }
  EXPECT_GT(max_lift, 0.005);  // the pull really deformed it (more than 5 mm)
  EXPECT_GT(max_energy, 0.0);
  EXPECT_LT(body.KineticEnergy(), 1e-6 * max_energy);
  EXPECT_LT(body.state().displacement_m.cwiseAbs().maxCoeff(), 1e-3 * max_lift);
  return max_lift;
}

TEST(FemBodyTest, GallbladderPulledAndReleasedComesToRestWithBoundedEnergy) {
  for (TimeIntegrator integrator : {TimeIntegrator::kBackwardEuler, TimeIntegrator::kNewmark}) {
    SCOPED_TRACE(integrator == TimeIntegrator::kNewmark ? "Newmark" : "backward Euler");
    const double exact = PullAndRelease(LinearSolverKind::kCholmod, 1, integrator);
    // Refactorising every 5th step (the stale factor preconditions PCG) or plain PCG: same motion.
    EXPECT_NEAR(PullAndRelease(LinearSolverKind::kCholmod, 5, integrator), exact, 1e-6 * exact);
    EXPECT_NEAR(PullAndRelease(LinearSolverKind::kPcg, 1, integrator), exact, 1e-4 * exact);
    EXPECT_NEAR(PullAndRelease(LinearSolverKind::kRotatedFactorPcg, 1, integrator), exact, 1e-6 * exact);
  }
}

// A corner pushed through its own tets (several inverted) and let go: corotational elements turn
// them back. Every step is accepted, the energy never rises above the start's (no external work),
// and the body ends at rest with every tet the right way out. Exact CHOLMOD steps and the shipped
// rotated-factor PCG (whose vectorised pass hands det F <= 0.2 lanes to the scalar rule).
TEST(FemBodyTest, InvertedTetsOfACrushedCornerTurnBackAndTheBodyComesToRest) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {4, 2, 2});
  const int corner = mesh.num_vertices() - 1;  // (0.08, 0.03, 0.03)
  for (LinearSolverKind solver : {LinearSolverKind::kCholmod, LinearSolverKind::kRotatedFactorPcg}) {
    SCOPED_TRACE(solver == LinearSolverKind::kCholmod ? "CHOLMOD" : "rotated factor PCG");
    const FemSettings s = DampedGallbladderSettings(solver, TimeIntegrator::kBackwardEuler);
    auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 0, 0.0))));
    FemBody body(model);
    Eigen::VectorXd u = Eigen::VectorXd::Zero(model->num_dofs());
    u.segment<3>(3 * corner) = Eigen::Vector3d(-0.03, -0.025, -0.025);  // past the cell's far corner
    body.SetState(u, Eigen::VectorXd::Zero(model->num_dofs()));
    auto inverted_tets = [&] {
      TetrahedralMesh now = mesh;
      now.vertices = body.CurrentPositions();
      int count = 0;
      for (int t = 0; t < now.num_tets(); ++t) count += SignedTetVolume(now, t) <= 0.0;
      return count;
    };
    ASSERT_GE(inverted_tets(), 2);
    const double energy0 = body.ElasticEnergy();
    ASSERT_GT(energy0, 0.0);
    for (int step = 0; step < 300; ++step) {
      const StepReport r = body.Step();
      ASSERT_TRUE(r.accepted) << r.rejection_reason;
      EXPECT_LE(body.KineticEnergy() + body.ElasticEnergy(), 1.001 * energy0) << "step " << step;
    }
    EXPECT_EQ(inverted_tets(), 0);
    EXPECT_LT(body.state().displacement_m.cwiseAbs().maxCoeff(), 1e-3 * 0.03);
    EXPECT_LT(body.KineticEnergy() + body.ElasticEnergy(), 1e-6 * energy0);
  }
}

// A corotational body on CHOLMOD with a refresh interval N refactorises on its first step and
// every Nth after it (a direct solve: no PCG iteration) and in between preconditions PCG with the
// stale factor (iterations > 0, to the tolerance); a linear body factorises once and never needs PCG.
TEST(FemBodyTest, CholmodRefactorisesACorotationalBodyEveryNthStepAndPreconditionsBetween) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {8, 3, 3});
  for (ElementModel element : {ElementModel::kCorotational, ElementModel::kLinear}) {
    FemSettings s = GallbladderNewmarkSettings(LinearSolverKind::kCholmod);
    s.element_model = element;
    s.cholmod_refresh_steps = 4;
    auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 0, 0.0))));
    FemBody body(model);
    Eigen::VectorXd pull = Eigen::VectorXd::Zero(model->num_dofs());
    pull.segment<3>(3 * (mesh.num_vertices() - 1)) = Eigen::Vector3d(0.05, 0.0, 0.1);
    body.SetExternalForces(pull);
    for (int step = 0; step < 12; ++step) {
      const StepReport r = body.Step();
      ASSERT_TRUE(r.accepted) << r.rejection_reason;
      // Factorised on the first step and, corotational, on every 4th; a linear body once only.
      EXPECT_EQ(r.factorised, step == 0 || (element == ElementModel::kCorotational && step % 4 == 0))
          << "step " << step;
      if (element == ElementModel::kLinear || step % 4 == 0) {
        EXPECT_EQ(r.solver_iterations, 0) << "step " << step;
        EXPECT_EQ(r.relative_residual, 0.0) << "step " << step;
      } else {
        EXPECT_GE(r.solver_iterations, 1) << "step " << step;
        EXPECT_LE(r.relative_residual, s.pcg_relative_tolerance) << "step " << step;
      }
    }
  }
}

// The paper's PCG starts from the last increment: a step of a steadily moving body takes fewer
// iterations than the same step started from zero (a fresh body given the same state), and both
// reach the same increment.
TEST(FemBodyTest, PcgWarmStartFromTheLastIncrementSavesIterations) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {8, 3, 3});
  FemSettings s;
  s.body_name = "gallbladder";
  s.solver = LinearSolverKind::kPcg;
  s.integrator = TimeIntegrator::kBackwardEuler;  // no acceleration state: SetState copies it all
  s.material = {2300.0, 0.45, 1000.0};
  s.rayleigh_mass_per_s = 1.0;
  s.pcg_relative_tolerance = 1e-10;
  s.pcg_max_iterations = 1000;
  auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 0, 0.0))));
  FemBody warm(model);
  warm.SetExternalForces(model->GravityForces({0, 0, -9.81}));
  for (int step = 0; step < 5; ++step) ASSERT_TRUE(warm.Step().accepted);
  FemBody cold(model);
  cold.SetExternalForces(warm.state().external_force_N);
  cold.SetState(warm.state().displacement_m, warm.state().velocity_m_per_s);
  const StepReport rw = warm.Step(), rc = cold.Step();
  ASSERT_TRUE(rw.accepted && rc.accepted);
  EXPECT_LE(rw.relative_residual, 1e-10);
  EXPECT_LE(rc.relative_residual, 1e-10);
  EXPECT_LT(rw.solver_iterations, rc.solver_iterations);
  const Eigen::VectorXd& u = warm.state().displacement_m;
  EXPECT_LT((u - cold.state().displacement_m).norm(), 1e-7 * u.norm());
}

// The rotated rest factor preconditions PCG on the true corotational system: driven to a tight
// tolerance it follows the exact (fresh CHOLMOD factor each step) trajectory of a body that is
// twisted about its long axis by a torque on its free end and pulled at a corner; so does the
// variant wrapped in Gauss-Seidel sweeps, in fewer iterations.
TEST(FemBodyTest, RotatedFactorPcgFollowsTheExactStepsOfATwistedPulledBody) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {8, 3, 3});
  const std::vector<int> free_end = NodesOnPlane(mesh, 0, 0.08);
  constexpr int kSteps = 60;
  constexpr int kRuns = 5;  // exact CHOLMOD, rotated factor, + Gauss-Seidel (1 sweep a side, float and
                            // double matrix), + 2 Gauss-Seidel sweeps a side
  std::vector<Eigen::VectorXd> trajectory[kRuns];
  double max_residual[kRuns] = {}, mean_iterations[kRuns] = {}, max_twist_rad = 0.0;
  for (int k = 0; k < kRuns; ++k) {
    FemSettings s;
    s.body_name = "gallbladder";
    s.element_model = ElementModel::kCorotational;
    s.integrator = TimeIntegrator::kNewmark;
    s.material = {2300.0, 0.45, 1000.0};
    s.time_step_s = 0.01;
    s.rayleigh_mass_per_s = 1.0;
    s.rayleigh_stiffness_s = 0.01;
    s.solver = k == 0 ? LinearSolverKind::kCholmod : LinearSolverKind::kRotatedFactorPcg;
    s.rotated_factor_gauss_seidel = k >= 2;
    s.rotated_factor_float_sweeps = k != 3;
    s.rotated_factor_sweeps = k == 4 ? 2 : 1;
    s.pcg_relative_tolerance = 1e-10;
    s.pcg_max_iterations = 200;
    auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 0, 0.0))));
    FemBody body(model);
    const int corner = mesh.num_vertices() - 1;
    for (int step = 0; step < kSteps; ++step) {
      Eigen::VectorXd f = Eigen::VectorXd::Zero(model->num_dofs());
      const Eigen::Vector3d center(0.08, 0.015, 0.015);
      for (int n : free_end) {  // a torque about x: 0.6 mN per cm from the axis
        const Eigen::Vector3d x = (mesh.vertices.row(n).transpose() + body.state().displacement_m.segment<3>(3 * n));
        f.segment<3>(3 * n) = 0.06 * Eigen::Vector3d::UnitX().cross(x - center);
      }
      f.segment<3>(3 * corner) += 0.02 * std::sin(2.0 * M_PI * 2.0 * body.state().time_s) * Eigen::Vector3d(0.3, 0, 1);
      body.SetExternalForces(f);
      const StepReport r = body.Step();
      ASSERT_TRUE(r.accepted) << r.rejection_reason;
      trajectory[k].push_back(body.state().displacement_m);
      // Twist of the free end: turn about x of the edge from its first to its last node.
      const Eigen::Vector3d a = mesh.vertices.row(free_end.front()).transpose() +
                                body.state().displacement_m.segment<3>(3 * free_end.front());
      const Eigen::Vector3d b =
          mesh.vertices.row(free_end.back()).transpose() + body.state().displacement_m.segment<3>(3 * free_end.back());
      max_twist_rad = std::max(max_twist_rad, std::abs(std::atan2(b.z() - a.z(), b.y() - a.y()) - M_PI / 4.0));
      max_residual[k] = std::max(max_residual[k], r.relative_residual);
      mean_iterations[k] += static_cast<double>(r.solver_iterations) / kSteps;
    }
  }
  EXPECT_GT(max_twist_rad, 0.3);  // a large rotation, where a linear model would be wrong
  for (int k = 1; k < kRuns; ++k) {
    double max_difference = 0.0, max_displacement = 0.0;
    for (int step = 0; step < kSteps; ++step) {
      max_difference = std::max(max_difference, (trajectory[k][step] - trajectory[0][step]).cwiseAbs().maxCoeff());
      max_displacement = std::max(max_displacement, trajectory[0][step].cwiseAbs().maxCoeff());
    }
    std::printf(
        "twisted body (free end turned %.2f rad, max |u| %.4f m): rotated-factor PCG%s %.1f iterations per step, "
        "max residual %.2e, max difference from exact %.2e m\n",
        max_twist_rad, max_displacement,
        k == 2   ? " + Gauss-Seidel"
        : k == 3 ? " + Gauss-Seidel (double)"
        : k == 4 ? " + 2 Gauss-Seidel sweeps"
                 : "",
        mean_iterations[k], max_residual[k], max_difference);
    EXPECT_LE(max_residual[k], 1e-10);
    EXPECT_LT(mean_iterations[k], 30.0);
    EXPECT_LT(max_difference, 1e-6 * max_displacement);
  }
  EXPECT_LT(mean_iterations[2], mean_iterations[1]);
  EXPECT_LT(mean_iterations[4], mean_iterations[2]);
}

// Consistent mass, backward Euler and nodes fixed along one axis only (those keep R = I in the
// preconditioner): the rotated-factor steps, with and without Gauss-Seidel, still match exact ones.
// SOFA's beam benchmark (bench/fem/fem_beam_bench.cpp) on a coarser grid: the rotated-factor PCG
// stopped at SOFA's CG tolerance (relative residual 1e-6) follows the exact steps (CHOLMOD on each
// step's system) to a few parts in 1e8 of the beam's sag, while 20 Jacobi-preconditioned CG
// iterations a step (SOFA's iteration cap, with a preconditioner SOFA's CG does not have) drift by
// parts in a thousand: the accuracy the beam benchmark's steps/s figures are quoted at.
TEST(FemBodyTest, SofaBeamAtSofasToleranceFollowsTheExactStepsWhereTwentyCgIterationsDoNot) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({16.0, 4.0, 4.0}, {19, 4, 4});
  constexpr int kSteps = 80;
  auto run = [&](LinearSolverKind solver, double tolerance, int max_iterations) {
    FemSettings s;
    s.body_name = "sofa beam";
    s.material = {2000.0, 0.3, 50.0 / (16.0 * 4.0 * 4.0)};
    s.element_model = ElementModel::kCorotational;
    s.integrator = TimeIntegrator::kBackwardEuler;
    s.mass_model = MassModel::kLumped;
    s.solver = solver;
    s.pcg_relative_tolerance = tolerance;
    s.pcg_max_iterations = max_iterations;
    s.time_step_s = 0.01;
    s.rayleigh_mass_per_s = 0.1;
    s.rayleigh_stiffness_s = 0.1;
    auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 0, 0.0))));
    FemBody body(model);
    body.SetExternalForces(model->GravityForces({0.0, -9.0, 0.0}));
    std::vector<Eigen::VectorXd> trajectory;
    for (int step = 0; step < kSteps; ++step) {
      const StepReport r = body.Step();
      EXPECT_TRUE(r.accepted) << r.rejection_reason;
      if (solver == LinearSolverKind::kRotatedFactorPcg) {
        EXPECT_LE(r.relative_residual, tolerance);
      }
      trajectory.push_back(body.state().displacement_m);
    }
    return trajectory;
  };
  const auto exact = run(LinearSolverKind::kCholmod, 1e-8, 20);
  double sag = 0.0;
  for (const Eigen::VectorXd& u : exact) sag = std::max(sag, u.cwiseAbs().maxCoeff());
  auto deviation = [&](const std::vector<Eigen::VectorXd>& trajectory) {
    double d = 0.0;
    for (int k = 0; k < kSteps; ++k) d = std::max(d, (trajectory[k] - exact[k]).cwiseAbs().maxCoeff());
    return d / sag;
  };
  const double rotated_factor = deviation(run(LinearSolverKind::kRotatedFactorPcg, 1e-6, 100));
  const double twenty_cg = deviation(run(LinearSolverKind::kPcg, 1e-6, 20));
  std::printf("sag %.3f m; deviation from the exact steps: rotated factor to 1e-6 %.2e, 20 Jacobi-CG %.2e\n", sag,
              rotated_factor, twenty_cg);
  EXPECT_GT(sag, 1.0);  // a large, rotating deflection: 16 m beam, E = 2 kPa
  EXPECT_LT(rotated_factor, 1e-6);
  EXPECT_GT(twenty_cg, 1e3 * rotated_factor);
}

TEST(FemBodyTest, RotatedFactorPcgMatchesExactStepsWithConsistentMassAndPartlyFixedNodes) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {8, 3, 3});
  std::vector<DirichletNode> fixed = Clamp(NodesOnPlane(mesh, 0, 0.0));
  for (int n : NodesOnPlane(mesh, 2, 0.0))
    if (mesh.vertices(n, 0) > 0.0) fixed.push_back({n, {false, false, true}});  // a floor: z held
  Eigen::VectorXd final_u[3];
  for (int k = 0; k < 3; ++k) {
    FemSettings s;
    s.element_model = ElementModel::kCorotational;
    s.integrator = TimeIntegrator::kBackwardEuler;
    s.mass_model = MassModel::kConsistent;
    s.material = {2300.0, 0.45, 1000.0};
    s.rayleigh_mass_per_s = 1.0;
    s.solver = k == 0 ? LinearSolverKind::kCholmod : LinearSolverKind::kRotatedFactorPcg;
    s.rotated_factor_gauss_seidel = k == 2;
    s.pcg_relative_tolerance = 1e-11;
    s.pcg_max_iterations = 200;
    auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, fixed));
    FemBody body(model);
    Eigen::VectorXd f = model->GravityForces({0, 0, 9.81});  // pulls the body up off its floor
    f.segment<3>(3 * (mesh.num_vertices() - 1)) += Eigen::Vector3d(0.0, 0.05, 0.05);
    body.SetExternalForces(f);
    for (int step = 0; step < 20; ++step) {
      const StepReport r = body.Step();
      ASSERT_TRUE(r.accepted) << r.rejection_reason;
      if (k > 0) {
        EXPECT_LE(r.relative_residual, 1e-11) << "step " << step;
      }
    }
    final_u[k] = body.state().displacement_m;
    for (const DirichletNode& d : fixed)
      for (int axis = 0; axis < 3; ++axis)
        if (d.axes[axis]) {
          EXPECT_EQ(final_u[k][3 * d.node + axis], 0.0);
        }
  }
  EXPECT_GT(final_u[0].cwiseAbs().maxCoeff(), 0.005);  // moved by more than 5 mm
  EXPECT_LT((final_u[1] - final_u[0]).cwiseAbs().maxCoeff(), 1e-8 * final_u[0].cwiseAbs().maxCoeff());
  EXPECT_LT((final_u[2] - final_u[0]).cwiseAbs().maxCoeff(), 1e-8 * final_u[0].cwiseAbs().maxCoeff());
}

// A beam falling under gravity (SOFA's scene, small): the motion is smooth, so the warm start
// extrapolated from the last increments (IncrementExtrapolation, up to fourth order) leaves PCG
// little to do, and the steps still follow the exact CHOLMOD ones to the tolerance. A second
// body that also gets a jerky sideways force every other step checks that the warm start falls
// back to low orders there instead of amplifying the jerk (its steps are exact too).
TEST(FemBodyTest, RotatedFactorPcgWarmStartFromExtrapolatedIncrements) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({16.0, 4.0, 4.0}, {16, 4, 4});
  for (bool jerky : {false, true}) {
    Eigen::VectorXd final_u[2];
    double late_iterations = 0.0;
    for (int k = 0; k < 2; ++k) {
      FemSettings s;
      s.body_name = "falling beam";
      s.element_model = ElementModel::kCorotational;
      s.integrator = TimeIntegrator::kBackwardEuler;
      s.material = {2000.0, 0.3, 50.0 / (16.0 * 4.0 * 4.0)};
      s.rayleigh_mass_per_s = 0.1;
      s.rayleigh_stiffness_s = 0.1;
      s.solver = k == 0 ? LinearSolverKind::kCholmod : LinearSolverKind::kRotatedFactorPcg;
      s.pcg_relative_tolerance = 1e-8;
      s.pcg_max_iterations = 200;
      auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 0, 0.0))));
      FemBody body(model);
      const Eigen::VectorXd gravity = model->GravityForces({0.0, -9.0, 0.0});
      for (int step = 0; step < 40; ++step) {
        Eigen::VectorXd f = gravity;
        if (jerky && step % 2) f.segment<3>(3 * (mesh.num_vertices() - 1)) += Eigen::Vector3d(0.0, 0.0, 0.5);
        body.SetExternalForces(f);
        const StepReport r = body.Step();
        ASSERT_TRUE(r.accepted) << r.rejection_reason;
        if (k == 1) {
          EXPECT_LE(r.relative_residual, 1e-8) << "step " << step;
        }
        if (k == 1 && step >= 20) late_iterations += r.solver_iterations / 20.0;
      }
      final_u[k] = body.state().displacement_m;
    }
    std::printf("falling beam%s: %.2f PCG iterations per step over steps 20-39, max |u| %.3f m\n",
                jerky ? " with a jerky force" : "", late_iterations, final_u[0].cwiseAbs().maxCoeff());
    EXPECT_GT(final_u[0].cwiseAbs().maxCoeff(), 0.5);
    EXPECT_LT((final_u[1] - final_u[0]).cwiseAbs().maxCoeff(), 1e-8 * final_u[0].cwiseAbs().maxCoeff());
    // Measured: 1.15 smooth (3.0 with the linear extrapolation alone), 2.95 jerky (3.0).
    EXPECT_LT(late_iterations, jerky ? 3.5 : 2.0);
  }
}

// The contact solver's compliance needs accurate solves (tolerance 1e-12): PCG preconditioned by
// the float rest factor (a 2,900-node body: CHOLMOD picks a supernodal factor, so the float copy is
// used) still gets there, and agrees with the CHOLMOD compliance.
TEST(FemBodyTest, RotatedFactorPcgComplianceMatchesCholmod) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {28, 9, 9});
  const std::vector<TetLocation> points = {{mesh.num_tets() - 1, {0.1, 0.2, 0.3, 0.4}},
                                           {mesh.num_tets() / 2, {0.25, 0.25, 0.25, 0.25}}};
  Eigen::MatrixXd delassus[2];
  for (int k = 0; k < 2; ++k) {
    FemSettings s;
    s.element_model = ElementModel::kCorotational;
    s.material = {2300.0, 0.45, 1000.0};
    s.solver = k == 0 ? LinearSolverKind::kCholmod : LinearSolverKind::kRotatedFactorPcg;
    auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 0, 0.0))));
    FemBody body(model);
    delassus[k] = body.Compliance(points).delassus;
  }
  EXPECT_LT((delassus[1] - delassus[0]).cwiseAbs().maxCoeff(), 1e-9 * delassus[0].cwiseAbs().maxCoeff());
}

// A linear body's rest factor is its system matrix: PCG converges in one iteration with the double
// factor (two or three with the float copy, at most six with the half one), also after attachment
// springs change the system (the rest factor is rebuilt with them).
TEST(FemBodyTest, RotatedFactorPcgSolvesALinearBodyInOneIterationWithAttachments) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {8, 3, 3});
  for (int precision : {0, 1, 2}) {  // double, float, half
    const bool single = precision > 0;
    FemSettings s;
    s.element_model = ElementModel::kLinear;
    s.solver = LinearSolverKind::kRotatedFactorPcg;
    s.rotated_factor_single_precision = single;
    s.rotated_factor_half_precision = precision == 2;
    s.pcg_relative_tolerance = 1e-12;
    s.rotated_factor_adopt_steps = 0;  // rebuilt in the next step (the background path: below)
    auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 0, 0.0))));
    FemBody body(model);
    body.SetExternalForces(model->GravityForces({0, 0, -9.81}));
    const int expected_iterations = precision == 2 ? 6 : single ? 3 : 1;
    StepReport r = body.Step();
    ASSERT_TRUE(r.accepted);
    EXPECT_LE(r.solver_iterations, expected_iterations) << "precision " << precision;
    EXPECT_LE(r.relative_residual, 1e-12);
    // P^-1 S is the identity up to the factor's rounding: its spectrum a point at 1.
    const double spread = precision == 2 ? 5e-3 : single ? 1e-5 : 1e-9;
    EXPECT_NEAR(r.solver_spectrum.smallest, 1.0, spread) << "precision " << precision;
    EXPECT_NEAR(r.solver_spectrum.largest, 1.0, spread) << "precision " << precision;
    body.SetAttachmentStiffness(Eigen::VectorXd::Constant(model->num_dofs(), 50.0),
                                Eigen::VectorXd::Constant(model->num_dofs(), 0.1));
    r = body.Step();
    ASSERT_TRUE(r.accepted);
    EXPECT_LE(r.solver_iterations, expected_iterations) << "precision " << precision;
    EXPECT_LE(r.relative_residual, 1e-12);
  }
}

// Springs cut mid-run (rotated_factor_adopt_steps > 0): the rest factor is rebuilt on a worker and
// adopted that many steps later. Until then the old factor preconditions the new system (more
// iterations, same tolerance); from the adopting step on, a linear body solves in one iteration
// again; every step equals the one of a body that rebuilds at once.
TEST(FemBodyTest, RotatedFactorRebuiltInTheBackgroundIsAdoptedAfterTheSetSteps) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {8, 3, 3});
  constexpr int kAdopt = 4;
  std::vector<Eigen::VectorXd> trajectory[2];
  std::vector<int> iterations[2];
  for (int run = 0; run < 2; ++run) {
    FemSettings s;
    s.element_model = ElementModel::kLinear;
    s.solver = LinearSolverKind::kRotatedFactorPcg;
    s.rotated_factor_single_precision = false;  // a linear body then solves in exactly one iteration
    s.pcg_relative_tolerance = 1e-12;
    s.pcg_max_iterations = 200;
    s.rotated_factor_adopt_steps = run == 0 ? 0 : kAdopt;
    auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 0, 0.0))));
    const int n = model->num_dofs();
    Eigen::VectorXd k = Eigen::VectorXd::Zero(n), d = Eigen::VectorXd::Zero(n);
    for (int v : NodesOnPlane(mesh, 2, 0.03))
      k.segment<3>(3 * v).setConstant(20.0), d.segment<3>(3 * v).setConstant(0.05);
    FemBody body(model);
    body.SetAttachmentStiffness(k, d);
    body.SetExternalForces(model->GravityForces({0, 0, -9.81}));
    for (int step = 0; step < 12; ++step) {
      if (step == 3) {  // cut the springs on the far half of the top
        for (int v : NodesOnPlane(mesh, 2, 0.03))
          if (mesh.vertices(v, 0) > 0.04) k.segment<3>(3 * v).setZero(), d.segment<3>(3 * v).setZero();
        body.SetAttachmentStiffness(k, d);
      }
      const StepReport r = body.Step();
      ASSERT_TRUE(r.accepted) << r.rejection_reason;
      EXPECT_LE(r.relative_residual, 1e-12) << "run " << run << " step " << step;
      trajectory[run].push_back(body.state().displacement_m);
      iterations[run].push_back(r.solver_iterations);
    }
  }
  for (int step = 0; step < 12; ++step) {
    EXPECT_EQ(iterations[0][static_cast<size_t>(step)], 1) << step;  // the factor is always the system's
    const bool stale = step >= 3 && step < 3 + kAdopt - 1;           // the adopting step is the kAdopt-th after the cut
    if (stale)
      EXPECT_GT(iterations[1][static_cast<size_t>(step)], 1) << step;
    else
      EXPECT_EQ(iterations[1][static_cast<size_t>(step)], 1) << step;
    EXPECT_LT((trajectory[1][static_cast<size_t>(step)] - trajectory[0][static_cast<size_t>(step)]).norm(),
              1e-9 * trajectory[0][static_cast<size_t>(step)].norm())
        << step;
  }
}

// ElasticEnergy warm-starts the rotations from the last step (the SVD of every tet costs a step):
// the same energy as the cold SVD pass, on a body turned and stretched well away from rest.
TEST(FemBodyTest, ElasticEnergyMatchesTheColdSvdPass) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {8, 3, 3});
  FemSettings s;
  s.element_model = ElementModel::kCorotational;
  s.solver = LinearSolverKind::kRotatedFactorPcg;
  s.material = {2300.0, 0.45, 1000.0};
  s.pcg_max_iterations = 200;
  auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 0, 0.0))));
  FemBody body(model);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(model->num_dofs());
  for (int v : NodesOnPlane(mesh, 0, 0.08)) f.segment<3>(3 * v) = Eigen::Vector3d(0.02, 0.0, -0.05);
  body.SetExternalForces(f);
  for (int step = 0; step < 30; ++step) ASSERT_TRUE(body.Step().accepted);
  ASSERT_GT(body.state().displacement_m.cwiseAbs().maxCoeff(), 0.01);  // a large bend
  Eigen::VectorXd force;
  const double cold = ComputeElasticForces(*model, body.state().displacement_m, nullptr, &force);
  EXPECT_GT(cold, 0.0);
  EXPECT_NEAR(body.ElasticEnergy(), cold, 1e-12 * cold);
}

// The matrix-free rotated-factor solver (the tangent applied element by element in every product,
// the default; without Gauss-Seidel sweeps S is never assembled, with them only for the sweeps)
// takes the assembled one's steps: Newmark with Rayleigh stiffness damping (the damping product
// uses K_t too), lumped and consistent mass, a clamped end and a floor held along z, attachment
// springs on the free end.
TEST(FemBodyTest, MatrixFreeRotatedFactorStepsMatchTheAssembledOnes) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {8, 3, 3});
  std::vector<DirichletNode> fixed = Clamp(NodesOnPlane(mesh, 0, 0.0));
  for (int n : NodesOnPlane(mesh, 2, 0.0))
    if (mesh.vertices(n, 0) > 0.0) fixed.push_back({n, {false, false, true}});
  const std::vector<int> free_end = NodesOnPlane(mesh, 0, 0.08);
  for (bool gauss_seidel : {false, true}) {
    for (MassModel mass : {MassModel::kLumped, MassModel::kConsistent}) {
      std::vector<Eigen::VectorXd> trajectory[2];
      int iterations[2] = {0, 0};
      for (int matrix_free = 0; matrix_free < 2; ++matrix_free) {
        FemSettings s;
        s.rotated_factor_gauss_seidel = gauss_seidel;
        s.element_model = ElementModel::kCorotational;
        s.integrator = TimeIntegrator::kNewmark;
        s.mass_model = mass;
        s.material = {2300.0, 0.45, 1000.0};
        s.rayleigh_mass_per_s = 1.0;
        s.rayleigh_stiffness_s = 0.01;
        s.solver = LinearSolverKind::kRotatedFactorPcg;
        s.rotated_factor_matrix_free = matrix_free == 1;
        s.pcg_relative_tolerance = 1e-12;
        s.pcg_max_iterations = 200;
        auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, fixed));
        FemBody body(model);
        Eigen::VectorXd springs = Eigen::VectorXd::Zero(model->num_dofs());
        for (int n : free_end) springs.segment<3>(3 * n).setConstant(1.0);
        body.SetAttachmentStiffness(springs, 0.01 * springs);
        for (int step = 0; step < 30; ++step) {
          Eigen::VectorXd f = Eigen::VectorXd::Zero(model->num_dofs());
          for (int n : free_end) {
            const Eigen::Vector3d x = mesh.vertices.row(n).transpose() + body.state().displacement_m.segment<3>(3 * n);
            f.segment<3>(3 * n) = 0.3 * Eigen::Vector3d::UnitX().cross(x - Eigen::Vector3d(0.08, 0.015, 0.015));
          }
          body.SetExternalForces(f);
          const StepReport r = body.Step();
          ASSERT_TRUE(r.accepted) << r.rejection_reason;
          EXPECT_LE(r.relative_residual, 1e-12);
          iterations[matrix_free] += r.solver_iterations;
          trajectory[matrix_free].push_back(body.state().displacement_m);
        }
      }
      double max_difference = 0.0, max_displacement = 0.0;
      for (size_t step = 0; step < trajectory[0].size(); ++step) {
        max_difference = std::max(max_difference, (trajectory[1][step] - trajectory[0][step]).cwiseAbs().maxCoeff());
        max_displacement = std::max(max_displacement, trajectory[0][step].cwiseAbs().maxCoeff());
      }
      std::printf(
          "matrix-free vs assembled rotated-factor steps (%s mass, %s): max |u| %.4f m, max difference %.2e m, "
          "iterations %d vs %d\n",
          mass == MassModel::kLumped ? "lumped" : "consistent", gauss_seidel ? "sweeps" : "no sweeps", max_displacement,
          max_difference, iterations[1], iterations[0]);
      EXPECT_GT(max_displacement, 0.002);
      EXPECT_LT(max_difference, 1e-9 * max_displacement);
      // With sweeps, the same preconditioner to rounding (with lumped mass the matrix-free body
      // keeps S only as the sweeps' float rows, written by the element pass): the same iterations,
      // one more or fewer over 30 steps at most. (Without sweeps it has no local solves, S being
      // nowhere.)
      if (gauss_seidel) {
        EXPECT_LE(std::abs(iterations[1] - iterations[0]), 1) << iterations[0] << " assembled, " << iterations[1];
      }
    }
  }
}

// The energy check after a rotated-factor PCG step takes du.K du from the product S du the solve
// leaves (b - r) instead of a product of its own: the reported energy must still be kinetic +
// elastic to second order, E(u) + f_int.du + du.K_t du / 2 with K_t assembled independently at the
// start of the step (fresh rotations), with springs, Rayleigh damping and partly fixed nodes.
TEST(FemBodyTest, StepEnergyFromTheSolverProductMatchesTheAssembledTangent) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {8, 3, 3});
  std::vector<DirichletNode> fixed = Clamp(NodesOnPlane(mesh, 0, 0.0));
  for (int n : NodesOnPlane(mesh, 2, 0.0))
    if (mesh.vertices(n, 0) > 0.0) fixed.push_back({n, {false, false, true}});
  const std::vector<int> free_end = NodesOnPlane(mesh, 0, 0.08);
  for (bool gauss_seidel : {false, true}) {
    FemSettings s = GallbladderNewmarkSettings(LinearSolverKind::kRotatedFactorPcg);
    s.rotated_factor_gauss_seidel = gauss_seidel;
    s.pcg_max_iterations = 200;  // tolerance: the default 1e-8
    auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, fixed));
    FemBody body(model);
    Eigen::VectorXd springs = Eigen::VectorXd::Zero(model->num_dofs());
    for (int n : free_end) springs.segment<3>(3 * n).setConstant(1.0);
    body.SetAttachmentStiffness(springs, 0.01 * springs);
    double max_error = 0.0, max_elastic_change = 0.0;
    for (int step = 0; step < 30; ++step) {
      Eigen::VectorXd f = Eigen::VectorXd::Zero(model->num_dofs());
      for (int n : free_end) f.segment<3>(3 * n) = Eigen::Vector3d(0.0, 0.02, 0.03 * std::sin(0.3 * step));
      body.SetExternalForces(f);
      const Eigen::VectorXd u0 = body.state().displacement_m;
      Eigen::VectorXd tangent, internal;
      std::vector<Eigen::Vector4d> cache;
      const double elastic0 = ComputeElasticForces(*model, u0, &tangent, &internal, &cache);
      const StepReport r = body.Step();
      ASSERT_TRUE(r.accepted) << r.rejection_reason;
      const Eigen::VectorXd du = body.state().displacement_m - u0;
      Eigen::VectorXd k_du;
      SymmetricPatternMultiply(model->pattern, tangent, du, k_du);
      const double elastic_change = internal.dot(du) + 0.5 * du.dot(k_du);
      const double expected = body.KineticEnergy() + elastic0 + elastic_change;
      max_error = std::max(max_error, std::abs(r.energy_J - expected));
      max_elastic_change = std::max(max_elastic_change, std::abs(elastic_change));
    }
    std::printf("step energy from the solver's S du (%s): max error %.2e J, max elastic change %.2e J\n",
                gauss_seidel ? "Gauss-Seidel" : "matrix-free", max_error, max_elastic_change);
    EXPECT_GT(max_elastic_change, 1e-7);
    EXPECT_LT(max_error, 1e-6 * max_elastic_change);
  }
}

TEST(FemBodyTest, PcgAndCholmodGiveTheSameStep) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {8, 3, 3});
  Eigen::VectorXd du[2];
  for (int k = 0; k < 2; ++k) {
    FemSettings s;
    s.element_model = ElementModel::kCorotational;
    s.solver = k == 0 ? LinearSolverKind::kCholmod : LinearSolverKind::kPcg;
    s.pcg_max_iterations = 500;
    s.pcg_relative_tolerance = 1e-12;
    auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 0, 0.0))));
    FemBody body(model);
    body.SetExternalForces(model->GravityForces({0, 0, -9.81}));
    for (int step = 0; step < 3; ++step) ASSERT_TRUE(body.Step().accepted);
    du[k] = body.state().displacement_m;
  }
  EXPECT_LT((du[0] - du[1]).norm(), 1e-9 * du[0].norm());
}

TEST(FemBodyTest, PcgHonoursTheIterationCapAndReportsItsResidual) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {8, 3, 3});
  FemSettings s;
  s.solver = LinearSolverKind::kPcg;  // paper: tol 1e-8, <= 20 iterations
  auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 0, 0.0))));
  FemBody body(model);
  body.SetExternalForces(model->GravityForces({0, 0, -9.81}));
  const StepReport r = body.Step();
  ASSERT_TRUE(r.accepted);
  EXPECT_GE(r.solver_iterations, 1);
  EXPECT_LE(r.solver_iterations, 20);
  EXPECT_GT(r.relative_residual, 0.0);
  EXPECT_TRUE(r.relative_residual <= 1e-8 || r.solver_iterations == 20);
}

// Compliance: the point response to a force lambda through J^T is W lambda (linear body, exact).
TEST(FemBodyTest, ComplianceGivesThePointResponseOfAStep) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {8, 3, 3});
  FemSettings s;
  s.element_model = ElementModel::kLinear;
  s.rayleigh_mass_per_s = 1.0;
  auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 0, 0.0))));
  std::vector<TetLocation> points = {{mesh.num_tets() - 1, {0.1, 0.2, 0.3, 0.4}}, {100, {0.25, 0.25, 0.25, 0.25}}};
  FemBody free_body(model), pushed_body(model);
  const PointCompliance c = free_body.Compliance(points);
  ASSERT_EQ(c.delassus.rows(), 6);
  EXPECT_LT((c.delassus - c.delassus.transpose()).cwiseAbs().maxCoeff(), 1e-9 * c.delassus.cwiseAbs().maxCoeff());
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(c.delassus).eigenvalues()[0], 0.0);

  Eigen::VectorXd lambda(6);
  lambda << 0.01, -0.02, 0.03, 0.0, 0.01, -0.01;
  Eigen::VectorXd jt_lambda = Eigen::VectorXd::Zero(model->num_dofs());
  for (int p = 0; p < 2; ++p)
    for (int k = 0; k < 4; ++k)
      jt_lambda.segment<3>(3 * mesh.tets(points[p].tet, k)) += points[p].weights[k] * lambda.segment<3>(3 * p);
  pushed_body.SetExternalForces(jt_lambda);
  ASSERT_TRUE(free_body.Step().accepted);
  ASSERT_TRUE(pushed_body.Step().accepted);
  const Eigen::VectorXd diff = pushed_body.state().displacement_m - free_body.state().displacement_m;
  Eigen::VectorXd point_motion(6);
  for (int p = 0; p < 2; ++p) {
    point_motion.segment<3>(3 * p).setZero();
    for (int k = 0; k < 4; ++k)
      point_motion.segment<3>(3 * p) += points[p].weights[k] * diff.segment<3>(3 * mesh.tets(points[p].tet, k));
  }
  EXPECT_LT((point_motion - c.delassus * lambda).norm(), 1e-9 * point_motion.norm());
  EXPECT_LT((diff - c.response * lambda).norm(), 1e-9 * diff.norm());
}

// Every solver and integrator: a force so large that the step overflows is rolled back, named and
// reported; the body keeps its last good state (the acceleration too, which Newmark's first step
// computes from equilibrium) and steps on once the input is sane again. The overflow comes on the
// body's second step, or on its first.
TEST(FemBodyTest, DivergentStepIsRolledBackAndReported) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {4, 2, 2});
  for (LinearSolverKind solver :
       {LinearSolverKind::kCholmod, LinearSolverKind::kPcg, LinearSolverKind::kRotatedFactorPcg})
    for (TimeIntegrator integrator : {TimeIntegrator::kBackwardEuler, TimeIntegrator::kNewmark})
      for (double overflow : {1e306, 1e200})
        for (bool first_step : {false, true}) {
          SCOPED_TRACE(::testing::Message()
                       << "solver " << static_cast<int>(solver) << ", integrator " << static_cast<int>(integrator)
                       << ", force " << overflow << (first_step ? ", first step" : ", second step"));
          FemSettings s;
          s.body_name = "gallbladder";
          s.solver = solver;
          s.integrator = integrator;
          auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 0, 0.0))));
          FemBody body(model);
          body.SetExternalForces(model->GravityForces({0, 0, -9.81}));
          if (!first_step) {
            ASSERT_TRUE(body.Step().accepted);
          }
          const FemState good = body.state();
          // |f| overflows (1e306 * sqrt(3n)) or the step's energy does (1e200 squared): either way
          // the step must not be committed.
          body.SetExternalForces(Eigen::VectorXd::Constant(model->num_dofs(), overflow));
          const StepReport r = body.Step();
          EXPECT_FALSE(r.accepted);
          EXPECT_NE(r.rejection_reason.find(first_step ? "gallbladder: step 0 rolled back"
                                                       : "gallbladder: step 1 rolled back"),
                    std::string::npos)
              << r.rejection_reason;
          EXPECT_EQ(body.state().displacement_m, good.displacement_m);
          EXPECT_EQ(body.state().velocity_m_per_s, good.velocity_m_per_s);
          EXPECT_EQ(body.state().acceleration_m_per_s2, good.acceleration_m_per_s2);
          EXPECT_EQ(body.state().steps, good.steps);
          EXPECT_TRUE(body.CurrentPositions().allFinite());
          // The body goes on once the input is sane again.
          body.SetExternalForces(model->GravityForces({0, 0, -9.81}));
          const StepReport next = body.Step();
          EXPECT_TRUE(next.accepted) << next.rejection_reason;
          EXPECT_TRUE(body.state().acceleration_m_per_s2.allFinite());
        }
}

// The energy bound itself, with every value finite: Newmark's average acceleration keeps an
// undamped linear mode's energy to rounding, so a bound below 1x the energy before must reject the
// step (named, state kept) and one above 1x must pass it.
TEST(FemBodyTest, StepWhoseEnergyExceedsTheBoundIsRolledBackAndReported) {
  const ModalBlock b = MakeModalBlock(TimeIntegrator::kNewmark, 20.0);
  const double amplitude = 1e-3;
  const double energy0 = 0.5 * b.omega * b.omega * amplitude * amplitude;
  for (double growth : {0.999, 1.001}) {
    SCOPED_TRACE(::testing::Message() << "max_energy_growth " << growth);
    auto model = std::make_shared<FemModel>(*b.model);
    model->settings.max_energy_growth = growth;
    model->settings.energy_floor_J = 0.0;
    FemBody body(model);
    body.SetState(amplitude * b.mode, Eigen::VectorXd::Zero(model->num_dofs()));
    const StepReport r = body.Step();
    if (growth < 1.0) {
      EXPECT_FALSE(r.accepted);
      EXPECT_NE(r.rejection_reason.find("modal block: step 0 rolled back: energy jumped from"), std::string::npos)
          << r.rejection_reason;
      EXPECT_EQ(body.state().displacement_m, amplitude * b.mode);
      EXPECT_EQ(body.state().steps, 0);
    } else {
      EXPECT_TRUE(r.accepted) << r.rejection_reason;
      EXPECT_NEAR(r.energy_J, energy0, 1e-9 * energy0);
      EXPECT_EQ(body.state().steps, 1);
    }
  }
}

// Newmark's trapezoidal rule conserves energy only for linear bodies: undamped, a corotational
// body set shaking at its highest modes (neighbouring nodes moving opposite ways) gains energy
// step after step (x1.03-4.4 a step in a scratch run: 3.4e-4 J to 1e86 J in 300 steps), each step
// under the per-step bound. The cumulative bound (the energy at the start plus the work done since,
// none here) stops it: the energy stays within max_energy_growth of where it started, and the
// steps that would pass it are rolled back and named.
TEST(FemBodyTest, EnergyPumpedUpStepByStepIsStoppedByTheCumulativeBound) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {8, 3, 3});
  FemSettings s;
  s.body_name = "gallbladder";
  s.element_model = ElementModel::kCorotational;
  s.integrator = TimeIntegrator::kNewmark;
  s.material = {2300.0, 0.45, 1000.0};
  s.time_step_s = 0.01;  // no Rayleigh damping: the FemSettings default
  auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 0, 0.0))));
  FemBody body(model);
  Eigen::VectorXd v = Eigen::VectorXd::Zero(model->num_dofs());
  for (int i = 0; i < mesh.num_vertices(); ++i) v[3 * i + 1] = i % 2 == 0 ? 0.1 : -0.1;
  body.SetState(Eigen::VectorXd::Zero(model->num_dofs()), v.cwiseProduct(model->free_dofs));
  const double energy0 = body.KineticEnergy();
  ASSERT_GT(energy0, 0.0);
  int rejected = 0;
  double max_energy = 0.0;
  for (int step = 0; step < 300; ++step) {
    const StepReport r = body.Step();
    if (!r.accepted) {
      ++rejected;
      EXPECT_NE(r.rejection_reason.find("gallbladder: step"), std::string::npos) << r.rejection_reason;
      EXPECT_NE(r.rejection_reason.find("energy"), std::string::npos) << r.rejection_reason;
    }
    max_energy = std::max(max_energy, body.KineticEnergy() + body.ElasticEnergy());
  }
  EXPECT_GT(rejected, 0);  // it really was pumping
  // The guard reads the step's second-order estimate of the elastic energy, which can read low
  // on such a state: the body's own energy is bounded with that slack.
  EXPECT_LT(max_energy, 10.0 * s.max_energy_growth * energy0);
  EXPECT_TRUE(body.CurrentPositions().allFinite());
}

// A state near the top of the doubles, moving further out: the step's increment, velocity and
// energy are finite, but u + du is not. The step is rolled back, not committed.
TEST(FemBodyTest, StepWhoseDisplacementWouldOverflowIsRolledBack) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {4, 2, 2});
  FemSettings s;
  s.body_name = "gallbladder";
  s.element_model = ElementModel::kLinear;
  s.material = {1e-320, 0.3, 1e-305};  // next to nothing resists or weighs
  s.time_step_s = 1.0;
  auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, {}));
  FemBody body(model);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(model->num_dofs()), v = u;
  for (int i = 0; i < mesh.num_vertices(); ++i) u[3 * i] = 1.79e308, v[3 * i] = 1e307;
  body.SetState(u, v);
  const StepReport r = body.Step();
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.rejection_reason.find("gallbladder: step 0 rolled back: non-finite displacement"), std::string::npos)
      << r.rejection_reason;
  EXPECT_TRUE(body.state().displacement_m.allFinite());
  EXPECT_EQ(body.state().displacement_m, u);
}

// Backward Euler with a step this long is statics (the mass term vanishes), which the clamped
// face allows; but the second step would take the simulation time past the doubles: it is rolled
// back, and time_s stays finite like the rest of the state.
TEST(FemBodyTest, StepWhoseTimeWouldOverflowIsRolledBack) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {4, 2, 2});
  FemSettings s;
  s.body_name = "gallbladder";
  s.time_step_s = 1e308;
  auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 0, 0.0))));
  FemBody body(model);
  body.SetExternalForces(model->GravityForces({0.0, 0.0, -9.81}));
  ASSERT_TRUE(body.Step().accepted);
  EXPECT_EQ(body.state().time_s, 1e308);
  const Eigen::VectorXd u = body.state().displacement_m;
  EXPECT_LT(u.minCoeff(), 0.0);  // it sagged
  const StepReport r = body.Step();
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.rejection_reason.find("gallbladder: step 1 rolled back: the simulation time overflows"),
            std::string::npos)
      << r.rejection_reason;
  EXPECT_EQ(body.state().time_s, 1e308);
  EXPECT_EQ(body.state().displacement_m, u);
}

TEST(FemBodyTest, NonFiniteOrMissizedInputIsRejectedAtTheDoor) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {4, 2, 2});
  FemSettings s;
  s.body_name = "gallbladder";
  auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 0, 0.0))));
  FemBody body(model);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(model->num_dofs());
  f[7] = std::nan("");
  try {
    body.SetExternalForces(f);
    FAIL() << "expected FemError";
  } catch (const FemError& e) {
    EXPECT_NE(std::string(e.what()).find("gallbladder: external force of node 2 (axis 1) is not finite"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(body.SetState(Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(3)), FemError);
  // A non-finite state is refused whole: the body keeps the state it had.
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model->num_dofs());
  Eigen::VectorXd v = zero;
  v[13] = std::numeric_limits<double>::infinity();
  Eigen::VectorXd u = zero;
  u[0] = 1e-3;
  try {
    body.SetState(u, v);
    FAIL() << "expected FemError";
  } catch (const FemError& e) {
    EXPECT_NE(std::string(e.what()).find("gallbladder: velocity of node 4 (axis 1) is not finite"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(body.state().displacement_m, zero);
  EXPECT_THROW(body.Compliance({{mesh.num_tets(), {0.25, 0.25, 0.25, 0.25}}}), FemError);
  // Weights that are not barycentric (summing to 2), or of a point far outside its tet: named.
  for (const Eigen::Vector4d& weights : {Eigen::Vector4d(0.5, 0.5, 0.5, 0.5), Eigen::Vector4d(1e300, 0, 0, 0),
                                         Eigen::Vector4d(1e200, -1e200, 1.0, 0.0)}) {
    try {
      body.Compliance({{3, {0.25, 0.25, 0.25, 0.25}}, {5, weights}});
      FAIL() << "expected FemError for weights " << weights.transpose();
    } catch (const FemError& e) {
      EXPECT_NE(std::string(e.what()).find("gallbladder: constrained point 1 has weights"), std::string::npos)
          << e.what();
    }
  }
  // Slightly outside its tet (LocateInTetMesh extrapolates) is fine.
  EXPECT_NO_THROW(body.Compliance({{5, {1.02, -0.01, -0.01, 0.0}}}));
}

// The rotated factor fits worst where a node's tets turn apart (around a pulled node); an exact
// solve on the nodes where they turn most apart, before and after the factor, cuts PCG's
// iterations, keeps the steps, and on every free node makes the preconditioner exact: one
// iteration a step. With and without the Gauss-Seidel sweeps (assembled system both ways).
TEST(FemBodyTest, LocalSolvesWhereTetsTurnApartCutIterationsAndOnEveryNodeMakeOneIteration) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {8, 3, 3});
  const int pulled = mesh.num_vertices() - 1;
  for (bool gauss_seidel : {true, false}) {
    int iterations[3] = {0, 0, 0}, max_iterations_all = 0;
    Eigen::VectorXd u[3];
    const int local_nodes[3] = {0, 16, mesh.num_vertices()};
    for (int k = 0; k < 3; ++k) {
      FemSettings s = GallbladderNewmarkSettings(LinearSolverKind::kRotatedFactorPcg);
      s.rotated_factor_gauss_seidel = gauss_seidel;
      s.rotated_factor_matrix_free = false;
      s.rotated_factor_float_sweeps = false;  // float sweeps leave a float-accurate residual
      s.rotated_factor_local_share = 1.0;
      s.rotated_factor_local_nodes_max = local_nodes[k];
      s.pcg_max_iterations = 200;
      auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, Clamp(NodesOnPlane(mesh, 0, 0.0))));
      FemBody body(model);
      Eigen::VectorXd f = Eigen::VectorXd::Zero(model->num_dofs());
      for (int step = 0; step < 30; ++step) {
        f.segment<3>(3 * pulled) = 0.2 * std::sin(0.25 * step) * Eigen::Vector3d(0.3, 0.0, 1.0);
        body.SetExternalForces(f);
        const StepReport r = body.Step();
        ASSERT_TRUE(r.accepted) << r.rejection_reason;
        EXPECT_LE(r.relative_residual, 1e-8);
        iterations[k] += r.solver_iterations;
        if (k == 2 && step >= 2) max_iterations_all = std::max(max_iterations_all, r.solver_iterations);
      }
      u[k] = body.state().displacement_m;
    }
    std::printf("%s: PCG iterations over 30 steps with 0 / 16 / all local nodes: %d / %d / %d\n",
                gauss_seidel ? "Gauss-Seidel" : "factor alone", iterations[0], iterations[1], iterations[2]);
    EXPECT_LT(iterations[1], 0.9 * iterations[0]);
    EXPECT_EQ(max_iterations_all, 1);  // from the third step on: every free node's tets have turned apart
    EXPECT_GT(u[0].norm(), 1e-3);
    for (int k = 1; k < 3; ++k) EXPECT_LT((u[k] - u[0]).norm(), 1e-6 * u[0].norm()) << k;
  }
}

// The node rotations that turn the rest factor are recomputed once the tets may have turned
// rotated_factor_rotation_refresh_rad since the last time (the element passes' largest turns,
// summed). A free body at rest is turned rigidly by 1 rad, twice: a threshold below 1 rad
// refreshes at each turn (as 0, every step, does), 1.5 rad only at the second (the turns add up),
// 3 rad at neither. Stale node frames cost iterations, never accuracy: every run takes the same
// steps to the tolerance.
TEST(FemBodyTest, NodeRotationsAreRecomputedOnceTheTetsMayHaveTurnedTheRefreshAngle) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, {6, 2, 2});
  const double thresholds[4] = {0.0, 0.5, 1.5, 3.0};
  int iterations[4][2];
  Eigen::VectorXd u[4][2];
  for (int k = 0; k < 4; ++k) {
    FemSettings s;
    s.body_name = "turned block";
    s.material = {2300.0, 0.45, 1000.0};
    s.element_model = ElementModel::kCorotational;
    s.integrator = TimeIntegrator::kBackwardEuler;
    s.solver = LinearSolverKind::kRotatedFactorPcg;
    s.pcg_relative_tolerance = 1e-10;
    s.pcg_max_iterations = 200;
    s.rotated_factor_rotation_refresh_rad = thresholds[k];
    auto model = std::make_shared<FemModel>(BuildFemModel(mesh, s, {}));
    FemBody body(model);
    Eigen::VectorXd stretch = Eigen::VectorXd::Zero(model->num_dofs());  // balanced: the block deforms
    for (int n : NodesOnPlane(mesh, 0, 0.0)) stretch[3 * n] = -0.05;
    for (int n : NodesOnPlane(mesh, 0, 0.08)) stretch[3 * n] = 0.05;
    body.SetExternalForces(stretch);
    ASSERT_TRUE(body.Step().accepted);  // the first solve computes the node rotations
    Eigen::Matrix3d turn = Eigen::Matrix3d::Identity();
    for (int j = 0; j < 2; ++j) {
      turn = Eigen::AngleAxisd(1.0, Eigen::Vector3d(0.2, 1.0, 0.4).normalized()).toRotationMatrix() * turn;
      Eigen::VectorXd turned(model->num_dofs());
      for (int n = 0; n < model->num_nodes(); ++n) {
        const Eigen::Vector3d x = mesh.vertices.row(n);
        turned.segment<3>(3 * n) = turn * x - x;
      }
      body.SetState(turned, Eigen::VectorXd::Zero(model->num_dofs()));
      const StepReport r = body.Step();
      ASSERT_TRUE(r.accepted) << r.rejection_reason;
      EXPECT_LE(r.relative_residual, 1e-10);
      iterations[k][j] = r.solver_iterations;
      u[k][j] = body.state().displacement_m - turned;
    }
  }
  std::printf(
      "iterations after the first / second 1 rad turn, refresh at 0 / 0.5 / 1.5 / 3 rad: %d %d / %d %d / %d %d "
      "/ %d %d\n",
      iterations[0][0], iterations[0][1], iterations[1][0], iterations[1][1], iterations[2][0], iterations[2][1],
      iterations[3][0], iterations[3][1]);
  for (int j = 0; j < 2; ++j) {
    EXPECT_EQ(iterations[1][j], iterations[0][j]) << j;
    EXPECT_GT(iterations[3][j], iterations[0][j] + 2) << j;
    EXPECT_GT(u[0][j].norm(), 1e-6);
    for (int k = 1; k < 4; ++k) EXPECT_LT((u[k][j] - u[0][j]).norm(), 1e-8 * u[0][j].norm()) << k << " " << j;
  }
  EXPECT_GT(iterations[2][0], iterations[0][0] + 2);  // 1 rad < 1.5: the frames stay
  EXPECT_EQ(iterations[2][1], iterations[0][1]);      // 2 rad >= 1.5: recomputed
}

}  // namespace
}  // namespace vesica::physics
