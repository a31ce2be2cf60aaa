// The rotated-factor preconditioner (rotated_factor_preconditioner.h) in every arrangement the FEM
// body uses: symmetric and positive definite, as PCG needs, and the exact inverse when the local
// solve covers every node.

#include "physics/fem/rotated_factor_preconditioner.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <cmath>

#include "physics/fem/cholmod_solver.h"
#include "physics/fem/elastic_forces.h"
#include "physics/fem/local_block_correction.h"
#include "physics/fem/pcg_solver.h"
#include "tests/fem/fem_test_support.h"

namespace vesica::physics {
namespace {

// A bent and twisted box: its tets turn apart, so the turned rest factor is not S's inverse.
struct Fixture {
  std::shared_ptr<FemModel> model;
  Eigen::VectorXd system, rest_system;
  Eigen::MatrixXd dense_system;
  CholmodSolver factor;
  std::vector<Eigen::Matrix3d> rotations;
  BlockJacobiPreconditioner jacobi;
  FloatBlockRows float_rows;

  Fixture() {
    const TetrahedralMesh mesh = MakeBoxTetMesh({0.04, 0.02, 0.02}, {4, 2, 2});
    FemSettings s;
    s.material = {2300.0, 0.45, 1000.0};
    s.element_model = ElementModel::kCorotational;
    model = std::make_shared<FemModel>(BuildFemModel(mesh, s, {}));
    const int n = model->num_nodes();
    Eigen::VectorXd u(3 * n);
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d x = mesh.vertices.row(i).transpose();
      const Eigen::Matrix3d turn =
          Eigen::AngleAxisd(20.0 * x.x(), Eigen::Vector3d::UnitX()).toRotationMatrix() *
          Eigen::AngleAxisd(15.0 * x.x() * x.x() / 0.04, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      u.segment<3>(3 * i) = turn * x - x;
    }
    Eigen::VectorXd tangent, force;
    std::vector<Eigen::Vector4d> cache;
    ComputeElasticForces(*model, u, &tangent, &force, &cache);
    system = 3.0 * tangent;
    rest_system = 3.0 * model->linear_stiffness_values;
    for (int i = 0; i < 3 * n; ++i) {
      system[model->pattern.diagonal_slot[i]] += 40.0 + 0.2 * i;
      rest_system[model->pattern.diagonal_slot[i]] += 40.0 + 0.2 * i;
    }
    Eigen::SparseMatrix<double> a = model->pattern.structure;
    a.makeCompressed();
    std::copy(system.data(), system.data() + system.size(), a.valuePtr());
    dense_system = Eigen::MatrixXd(a);
    EXPECT_TRUE(factor.Factorize(model->pattern, rest_system, true));
    for (int i = 0; i < n; ++i)
      rotations.push_back(
          Eigen::AngleAxisd(0.1 * i, Eigen::Vector3d(1.0, 0.5 * i, -0.3).normalized()).toRotationMatrix());
    jacobi.Compute(model->pattern, system);
    if (FloatBlockRows::available()) float_rows.Update(model->pattern, system);
  }

  RotatedFactorParts Parts(int sweeps, const LocalBlockCorrection* local, bool low_precision) const {
    RotatedFactorParts p;
    p.rest_factor = &factor;
    p.single_precision = low_precision;
    p.node_rotations = &rotations;
    p.sweeps = sweeps;
    p.pattern = &model->pattern;
    p.system_values = &system;
    p.float_rows = low_precision && FloatBlockRows::available() ? &float_rows : nullptr;
    p.inverse_diagonal = &jacobi.inverse_blocks();
    p.local = local;
    return p;
  }
};

Eigen::VectorXd Probe(int size, double phase) {
  Eigen::VectorXd v(size);
  for (int i = 0; i < size; ++i) v[i] = std::sin(1.7 * i + phase) + 0.3 * std::cos(0.37 * i * i + phase);
  return v;
}

TEST(RotatedFactorPreconditionerTest, SymmetricAndPositiveDefiniteInEveryArrangement) {
  Fixture f;
  LocalBlockCorrection local;
  ASSERT_TRUE(local.Compute(f.model->pattern, f.system, {4, 9, 22, 30, 31}));
  const int size = f.model->num_dofs();
  const Eigen::VectorXd a = Probe(size, 0.0), b = Probe(size, 1.3);
  RotatedFactorPreconditioner pre;
  for (bool low_precision : {false, true})
    for (int sweeps : {0, 1, 2})
      for (const LocalBlockCorrection* l : std::vector<const LocalBlockCorrection*>{nullptr, &local}) {
        const RotatedFactorParts parts = f.Parts(sweeps, l, low_precision);
        Eigen::VectorXd pa, pb;
        pre.Apply(parts, a, pa);
        pre.Apply(parts, b, pb);
        // Double everywhere: symmetric to rounding; the float sweeps and the half factor round
        // each application at ~1e-7..1e-4 (a preconditioner needs no more).
        const double tolerance = low_precision ? 1e-3 : 1e-12;
        SCOPED_TRACE(::testing::Message()
                     << "sweeps " << sweeps << (l ? ", local" : "") << (low_precision ? ", low precision" : ""));
        EXPECT_LT(std::abs(a.dot(pb) - b.dot(pa)), tolerance * a.norm() * pb.norm());
        EXPECT_GT(a.dot(pa), 0.0);
        EXPECT_GT(b.dot(pb), 0.0);
        // Close to S^-1 (what it is for): the preconditioned residual of S^-1 b is small.
        const Eigen::VectorXd exact = f.dense_system.llt().solve(b);
        EXPECT_LT((pb - exact).norm(), 0.9 * exact.norm());
      }
}

TEST(RotatedFactorPreconditionerTest, LocalSolveOnEveryNodeIsTheExactInverse) {
  Fixture f;
  std::vector<int> all(f.model->num_nodes());
  for (int i = 0; i < f.model->num_nodes(); ++i) all[i] = i;
  LocalBlockCorrection local;
  ASSERT_TRUE(local.Compute(f.model->pattern, f.system, all));
  const Eigen::VectorXd b = Probe(f.model->num_dofs(), 0.4);
  const Eigen::VectorXd exact = f.dense_system.llt().solve(b);
  RotatedFactorPreconditioner pre;
  for (int sweeps : {0, 1}) {
    Eigen::VectorXd z;
    pre.Apply(f.Parts(sweeps, &local, false), b, z);
    EXPECT_LT((z - exact).norm(), 1e-10 * exact.norm()) << sweeps;
  }
  // Without it the turned factor of the rest system is not: the twist is what it misses.
  Eigen::VectorXd z;
  pre.Apply(f.Parts(0, nullptr, false), b, z);
  EXPECT_GT((z - exact).norm(), 1e-2 * exact.norm());
}

}  // namespace
}  // namespace vesica::physics
