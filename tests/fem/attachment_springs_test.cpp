// FemBody::SetAttachmentStiffness: springs to outside anchors whose forces come in as external
// forces and whose stiffness/damping the step treats implicitly (physics/fem/attachment_springs.h).

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <limits>

#include "physics/fem/fem_body.h"
#include "physics/fem/fem_error.h"
#include "physics/fem/time_integrator.h"
#include "tests/fem/fem_test_support.h"

namespace vesica::physics {
namespace {

struct Variant {
  ElementModel element;
  LinearSolverKind solver;
};
const Variant kVariants[] = {{ElementModel::kLinear, LinearSolverKind::kPcg},
                             {ElementModel::kLinear, LinearSolverKind::kCholmod},
                             {ElementModel::kCorotational, LinearSolverKind::kPcg},
                             {ElementModel::kCorotational, LinearSolverKind::kCholmod}};

std::string Name(const Variant& v) {
  return std::string(v.element == ElementModel::kLinear ? "linear" : "corotational") + "/" +
         (v.solver == LinearSolverKind::kPcg ? "pcg" : "cholmod");
}

// A free-floating gallbladder-sized block (no fixed nodes): its only support is the springs.
std::shared_ptr<FemModel> FreeBlock(const Variant& v, TimeIntegrator integrator, double h, double density = 1000.0,
                                    double youngs = 2300.0) {
  FemSettings s;
  s.body_name = "gallbladder";
  s.element_model = v.element;
  s.solver = v.solver;
  s.integrator = integrator;
  s.time_step_s = h;
  s.material = {youngs, 0.45, density};
  s.pcg_relative_tolerance = 1e-13;
  s.pcg_max_iterations = 5000;
  return std::make_shared<FemModel>(BuildFemModel(MakeBoxTetMesh({0.04, 0.02, 0.02}, {4, 2, 2}), s, {}));
}

// The step's system S = c_M M + c_D (D + D_a) + K + K_a at rest, dense.
Eigen::MatrixXd DenseSystem(const FemModel& m, const Eigen::VectorXd& k, const Eigen::VectorXd& d) {
  const SystemCoefficients c = IntegratorCoefficients(m.settings);
  const Eigen::MatrixXd stiffness(PatternMatrix(m.pattern, m.linear_stiffness_values));
  const Eigen::MatrixXd mass = m.lumped_mass_kg.asDiagonal();
  const FemSettings& s = m.settings;
  return (c.mass + c.damping * s.rayleigh_mass_per_s) * mass + (1.0 + c.damping * s.rayleigh_stiffness_s) * stiffness +
         Eigen::MatrixXd((k + c.damping * d).asDiagonal());
}

// Static: one backward-Euler step with h so long that M/h^2 vanishes (4e-17 of k) solves
// (K + K_a) u = f: the springs act as fixed-anchor stiffness.
TEST(AttachmentSpringsTest, StaticDeflectionEqualsFixedAnchorStiffness) {
  for (const Variant& v : kVariants) {
    const auto model = FreeBlock(v, TimeIntegrator::kBackwardEuler, 1e6);
    const int n = model->num_dofs();
    Eigen::VectorXd k(n);
    for (int i = 0; i < n; ++i) k[i] = 20.0 * (1.0 + 0.5 * std::sin(1.0 + i));  // N/m, uneven
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
    // (a) a load f_i = k_i t on every dof translates the body rigidly: u = f/k at each node.
    {
      FemBody body(model);
      body.SetAttachmentStiffness(k, zero);
      const Eigen::Vector3d t(1e-3, -2e-3, 0.5e-3);
      Eigen::VectorXd f(n);
      for (int i = 0; i < n; ++i) f[i] = k[i] * t[i % 3];
      body.SetExternalForces(f);
      ASSERT_TRUE(body.Step().accepted) << Name(v);
      for (int i = 0; i < n; ++i)
        EXPECT_NEAR(body.state().displacement_m[i], f[i] / k[i], 1e-9 * std::abs(f[i] / k[i]))
            << Name(v) << " dof " << i;
    }
    // (b) a point load at one corner deforms the body: u = (K + K_a)^-1 f.
    {
      FemBody body(model);
      body.SetAttachmentStiffness(k, zero);
      Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
      f.segment<3>(3 * (model->num_nodes() - 1)) = Eigen::Vector3d(0.002, 0.001, -0.003);  // N
      body.SetExternalForces(f);
      ASSERT_TRUE(body.Step().accepted) << Name(v);
      const Eigen::VectorXd expected = DenseSystem(*model, k, zero).ldlt().solve(f);
      EXPECT_LT((body.state().displacement_m - expected).norm(), 1e-9 * expected.norm()) << Name(v);
    }
  }
}

// Rigid translation with k_i = omega^2 m_i on every dof: the body is a set of lumped-mass nodes on
// springs (K u = 0 for a translation). The scene's part: f_ext = -k u - d v at the start of each step.
struct Oscillation {
  std::vector<double> displacement;  // along the translation direction, per step (0 = start)
  std::vector<double> velocity;
};

Oscillation Oscillate(const Variant& v, TimeIntegrator integrator, double omega, double h, double zeta, int steps,
                      bool implicit = true, double density = 1000.0) {
  auto model = FreeBlock(v, integrator, h, density);
  model->settings.max_energy_growth = 1e300;  // let an explicit run show its growth
  const int n = model->num_dofs();
  const Eigen::VectorXd k = omega * omega * model->lumped_mass_kg;
  const Eigen::VectorXd d = 2.0 * zeta * omega * model->lumped_mass_kg;
  FemBody body(model);
  if (implicit) body.SetAttachmentStiffness(k, d);
  const Eigen::Vector3d dir = Eigen::Vector3d(1.0, 2.0, 3.0).normalized();
  const Eigen::VectorXd mode = dir.replicate(model->num_nodes(), 1);
  body.SetState(1e-3 * mode, Eigen::VectorXd::Zero(n));
  Oscillation o;
  const double mode_norm2 = mode.squaredNorm();
  for (int step = 0; step <= steps; ++step) {
    const FemState& st = body.state();
    o.displacement.push_back(mode.dot(st.displacement_m) / mode_norm2);
    o.velocity.push_back(mode.dot(st.velocity_m_per_s) / mode_norm2);
    // Every node must move with the mode (no deformation): checked through the residual.
    const double scale = std::max(1e-3, std::abs(o.displacement.back())) * std::sqrt(mode_norm2);
    EXPECT_LT((st.displacement_m - o.displacement.back() * mode).norm(), 1e-9 * scale) << Name(v) << " step " << step;
    if (step == steps) break;
    body.SetExternalForces(-k.cwiseProduct(st.displacement_m) - d.cwiseProduct(st.velocity_m_per_s));
    const StepReport r = body.Step();
    if (!r.accepted) ADD_FAILURE() << r.rejection_reason;
  }
  return o;
}

TEST(AttachmentSpringsTest, NewmarkConservesASpringModeAtSqrtKOverM) {
  const double omega = 2.0 * M_PI * 3.0, h = 0.01;  // omega h = 0.19
  for (const Variant& v : kVariants) {
    const Oscillation o = Oscillate(v, TimeIntegrator::kNewmark, omega, h, 0.0, 1000);
    // Average acceleration: |z| = |u + i v/omega| conserved; phase 2 atan(omega h / 2) per step.
    const double theta = 2.0 * std::atan(omega * h / 2.0);
    for (size_t s = 0; s < o.displacement.size(); ++s) {
      EXPECT_NEAR(std::hypot(o.displacement[s], o.velocity[s] / omega), 1e-3, 1e-9 * 1e-3) << Name(v) << " step " << s;
      EXPECT_NEAR(o.displacement[s], 1e-3 * std::cos(theta * static_cast<double>(s)), 1e-9 * 1e-3)
          << Name(v) << " step " << s;
    }
  }
}

TEST(AttachmentSpringsTest, BackwardEulerDecaysASpringModeAsOneOverSqrtOnePlusOmegaHSquared) {
  const double omega = 2.0 * M_PI * 3.0, h = 0.01;
  for (const Variant& v : kVariants) {
    const Oscillation o = Oscillate(v, TimeIntegrator::kBackwardEuler, omega, h, 0.0, 50);
    // z+ = z / (1 + i omega h) exactly.
    std::complex<double> z(1e-3, 0.0);
    for (size_t s = 1; s < o.displacement.size(); ++s) {
      z /= std::complex<double>(1.0, omega * h);
      const double before = std::hypot(o.displacement[s - 1], o.velocity[s - 1] / omega);
      const double after = std::hypot(o.displacement[s], o.velocity[s] / omega);
      EXPECT_NEAR(after / before, 1.0 / std::sqrt(1.0 + omega * h * omega * h), 1e-9) << Name(v) << " step " << s;
      EXPECT_NEAR(o.displacement[s], z.real(), 1e-9 * 1e-3) << Name(v) << " step " << s;
    }
  }
}

// Damping enters like Rayleigh D: the whole spring force at the end of the step is -k u+ - d v+,
// so the run follows the scalar integrator of m u'' + d u' + k u = 0 exactly.
TEST(AttachmentSpringsTest, DampedSpringModeFollowsTheScalarIntegrator) {
  const double omega = 2.0 * M_PI * 3.0, h = 0.01, zeta = 0.2;
  for (const TimeIntegrator integrator : {TimeIntegrator::kBackwardEuler, TimeIntegrator::kNewmark}) {
    const Variant v{ElementModel::kCorotational, LinearSolverKind::kCholmod};
    const Oscillation o = Oscillate(v, integrator, omega, h, zeta, 100);
    // Unit mass: k = omega^2, d = 2 zeta omega.
    const double k = omega * omega, d = 2.0 * zeta * omega;
    double u = 1e-3, vel = 0.0, a = -k * u;
    for (size_t s = 1; s < o.displacement.size(); ++s) {
      if (integrator == TimeIntegrator::kBackwardEuler) {
        vel = (vel - h * k * u) / (1.0 + h * d + h * h * k);
        u += h * vel;
      } else {  // beta 1/4, gamma 1/2: a+ = 4du/h^2 - 4v/h - a, v+ = 2du/h - v, a+ + d v+ + k (u + du) = 0
        const double du = (-k * u + 4.0 * vel / h + a + d * vel) / (4.0 / (h * h) + 2.0 * d / h + k);
        const double a_next = 4.0 * du / (h * h) - 4.0 * vel / h - a;
        vel += 0.5 * h * (a + a_next);
        a = a_next;
        u += du;
      }
      EXPECT_NEAR(o.displacement[s], u, 1e-9 * 1e-3) << "step " << s;
      EXPECT_NEAR(o.velocity[s], vel, 1e-9 * 1e-3 * omega) << "step " << s;
    }
  }
}

// The scene's case: k = 20 N/m on ~4e-5 kg nodes at h = 5 ms (omega h ~ 3.5). Applied only as forces
// (symplectic-Euler-like) the run explodes; with SetAttachmentStiffness it stays bounded.
TEST(AttachmentSpringsTest, StiffTissueOnLightNodesIsStableOnlyImplicitly) {
  // 0.04 x 0.02 x 0.02 m block, 45 nodes: density 112.5 kg/m^3 gives 4e-5 kg per node on average.
  const double density = 4e-5 * 45.0 / (0.04 * 0.02 * 0.02), h = 0.005;
  const Variant v{ElementModel::kCorotational, LinearSolverKind::kCholmod};
  auto probe = FreeBlock(v, TimeIntegrator::kBackwardEuler, h, density);
  ASSERT_NEAR(probe->lumped_mass_kg.mean(), 4e-5, 1e-12);
  // omega for the mean node mass; Oscillate uses k_i = omega^2 m_i, so 20 N/m on a mean node.
  const double omega = std::sqrt(20.0 / 4e-5);
  ASSERT_GT(omega * h, 3.5);
  for (const TimeIntegrator integrator : {TimeIntegrator::kBackwardEuler, TimeIntegrator::kNewmark}) {
    const Oscillation implicit = Oscillate(v, integrator, omega, h, 0.0, 200, true, density);
    for (size_t s = 0; s < implicit.displacement.size(); ++s)
      EXPECT_LE(std::hypot(implicit.displacement[s], implicit.velocity[s] / omega), 1e-3 * (1.0 + 1e-9)) << s;
  }
  const Oscillation explicit_run = Oscillate(v, TimeIntegrator::kBackwardEuler, omega, h, 0.0, 10, false, density);
  EXPECT_GT(std::abs(explicit_run.displacement.back()), 1e6 * 1e-3);  // ~ x10 per step
}

// Contacts see the springs: W = J S^-1 J^T with S holding k; a point on a spring of an (almost)
// absent body sees 1/k, since lumping gives its tet's nodes k w_i and sum w_i^2 / (k w_i) = 1/k.
TEST(AttachmentSpringsTest, ComplianceIncludesTheSprings) {
  const double k_spring = 20.0;
  const TetLocation point{5, {0.1, 0.2, 0.3, 0.4}};
  for (const Variant& v : kVariants) {
    // Almost absent body: E = 1e-6 Pa, 1e-6 kg/m^3 (its own stiffness/mass ~1e-9 of k).
    {
      const auto model = FreeBlock(v, TimeIntegrator::kBackwardEuler, 0.005, 1e-6, 1e-6);
      Eigen::VectorXd k = Eigen::VectorXd::Zero(model->num_dofs());
      for (int a = 0; a < 4; ++a)
        k.segment<3>(3 * model->rest_mesh.tets(point.tet, a)).setConstant(k_spring * point.weights[a]);
      // Nodes outside the spring's tet hang on the body alone: give them a weak spring too.
      for (int i = 0; i < k.size(); ++i) k[i] = std::max(k[i], 1e-3);
      FemBody body(model);
      body.SetAttachmentStiffness(k, Eigen::VectorXd::Zero(model->num_dofs()));
      const PointCompliance c = body.Compliance({point});
      EXPECT_LT((c.delassus - Eigen::Matrix3d::Identity() / k_spring).cwiseAbs().maxCoeff(), 1e-6 / k_spring)
          << Name(v);
    }
    // Real body, springs with damping: W equals the dense J S^-1 J^T.
    {
      const auto model = FreeBlock(v, TimeIntegrator::kNewmark, 0.005);
      const int n = model->num_dofs();
      Eigen::VectorXd k(n), d(n);
      for (int i = 0; i < n; ++i) k[i] = 20.0 * (1.0 + 0.5 * std::cos(i)), d[i] = 0.01 * (1.0 + std::sin(i));
      FemBody body(model);
      body.SetAttachmentStiffness(k, d);
      Eigen::MatrixXd jt = Eigen::MatrixXd::Zero(n, 3);
      for (int a = 0; a < 4; ++a)
        jt.block<3, 3>(3 * model->rest_mesh.tets(point.tet, a), 0) = point.weights[a] * Eigen::Matrix3d::Identity();
      const Eigen::MatrixXd expected = jt.transpose() * DenseSystem(*model, k, d).ldlt().solve(jt);
      const PointCompliance c = body.Compliance({point});
      EXPECT_LT((c.delassus - expected).cwiseAbs().maxCoeff(), 1e-9 * expected.cwiseAbs().maxCoeff()) << Name(v);
      // Cutting the springs (a linear CHOLMOD body must refactorise) changes W accordingly.
      const Eigen::VectorXd cut_k = k / 4.0;
      body.SetAttachmentStiffness(cut_k, d);
      const Eigen::MatrixXd expected_cut = jt.transpose() * DenseSystem(*model, cut_k, d).ldlt().solve(jt);
      const PointCompliance c_cut = body.Compliance({point});
      EXPECT_LT((c_cut.delassus - expected_cut).cwiseAbs().maxCoeff(), 1e-9 * expected_cut.cwiseAbs().maxCoeff())
          << Name(v);
      EXPECT_GT(c_cut.delassus(0, 0), c.delassus(0, 0) * (1.0 + 1e-6)) << Name(v);
    }
  }
}

// A step after cutting springs equals a fresh body that had the cut springs from the start.
TEST(AttachmentSpringsTest, ChangingTheSpringsMidRunIsTheSameAsStartingWithThem) {
  for (const Variant& v : kVariants) {
    const auto model = FreeBlock(v, TimeIntegrator::kNewmark, 0.005);
    const int n = model->num_dofs();
    const Eigen::VectorXd k = Eigen::VectorXd::Constant(n, 20.0), zero = Eigen::VectorXd::Zero(n);
    Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
    f.segment<3>(0) = Eigen::Vector3d(0.0, 0.0, 0.01);
    FemBody changed(model), fresh(model);
    changed.SetAttachmentStiffness(k, zero);
    changed.SetExternalForces(f);
    ASSERT_TRUE(changed.Step().accepted);
    changed.SetAttachmentStiffness(0.5 * k, zero);
    fresh.SetAttachmentStiffness(0.5 * k, zero);
    fresh.SetState(changed.state().displacement_m, changed.state().velocity_m_per_s);
    changed.SetState(changed.state().displacement_m, changed.state().velocity_m_per_s);  // same Newmark restart
    changed.SetExternalForces(f);
    fresh.SetExternalForces(f);
    ASSERT_TRUE(changed.Step().accepted);
    ASSERT_TRUE(fresh.Step().accepted);
    EXPECT_LT((changed.state().displacement_m - fresh.state().displacement_m).norm(),
              1e-9 * fresh.state().displacement_m.norm())
        << Name(v);
  }
}

TEST(AttachmentSpringsTest, BadInputNamesTheBodyAndTheDof) {
  const auto model = FreeBlock({ElementModel::kLinear, LinearSolverKind::kCholmod}, TimeIntegrator::kNewmark, 0.005);
  const int n = model->num_dofs();
  FemBody body(model);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  auto message = [&](const Eigen::VectorXd& k, const Eigen::VectorXd& d) {
    try {
      body.SetAttachmentStiffness(k, d);
    } catch (const FemError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  Eigen::VectorXd bad = zero;
  bad[7] = -1.0;
  EXPECT_NE(message(bad, zero).find("gallbladder: attachment stiffness of node 2 (axis 1, dof 7) is -1"),
            std::string::npos)
      << message(bad, zero);
  bad[7] = std::nan("");
  EXPECT_NE(message(zero, bad).find("gallbladder: attachment damping of node 2 (axis 1, dof 7)"), std::string::npos)
      << message(zero, bad);
  bad[7] = std::numeric_limits<double>::infinity();
  EXPECT_NE(message(bad, zero).find("must be finite and >= 0"), std::string::npos);
  EXPECT_NE(
      message(Eigen::VectorXd::Zero(5), zero).find("gallbladder: attachment stiffness has 5 entries, expected 3 x "),
      std::string::npos);
  EXPECT_NE(message(zero, Eigen::VectorXd::Zero(n + 3)).find("gallbladder: attachment damping has"), std::string::npos);
  // Rejected input leaves the body as it was (no springs): a free body under no load stays at rest.
  ASSERT_TRUE(body.Step().accepted);
  EXPECT_EQ(body.state().displacement_m.norm(), 0.0);
}

}  // namespace
}  // namespace vesica::physics
