#include "physics/fem/local_block_correction.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include "physics/fem/elastic_forces.h"
#include "physics/fem/pcg_solver.h"
#include "tests/fem/fem_test_support.h"

namespace vesica::physics {
namespace {

using testing::NodesOnPlane;

// An SPD system on a box's pattern: the rest stiffness plus a mass-like diagonal (no fixed nodes).
struct SmallSystem {
  std::shared_ptr<FemModel> model;
  Eigen::VectorXd values;
  Eigen::MatrixXd dense;
};

SmallSystem MakeSystem() {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.04, 0.02, 0.02}, {4, 2, 2});
  FemSettings s;
  s.material = {2300.0, 0.45, 1000.0};
  SmallSystem system;
  system.model = std::make_shared<FemModel>(BuildFemModel(mesh, s, testing::Clamp(NodesOnPlane(mesh, 0, 0.0))));
  const FemModel& m = *system.model;
  system.values = m.linear_stiffness_values;
  for (int i = 0; i < m.num_dofs(); ++i) system.values[m.pattern.diagonal_slot[i]] += 5.0 + 0.1 * i;
  Eigen::SparseMatrix<double> a = m.pattern.structure;
  a.makeCompressed();
  std::copy(system.values.data(), system.values.data() + system.values.size(), a.valuePtr());
  system.dense = Eigen::MatrixXd(a);
  return system;
}

TEST(LocalBlockCorrectionTest, OnEveryNodeItIsTheExactSolve) {
  const SmallSystem system = MakeSystem();
  const int nodes = system.model->num_nodes();
  std::vector<int> all(nodes);
  for (int n = 0; n < nodes; ++n) all[n] = nodes - 1 - n;  // any order
  LocalBlockCorrection local;
  ASSERT_TRUE(local.Compute(system.model->pattern, system.values, all));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(3 * nodes, -1.0, 2.0);
  Eigen::VectorXd z = Eigen::VectorXd::Zero(b.size()), r = b;
  local.Apply(r, z);
  const Eigen::VectorXd exact = system.dense.llt().solve(b);
  EXPECT_LT((z - exact).norm(), 1e-12 * exact.norm());
  EXPECT_LT(r.norm(), 1e-12 * b.norm());
}

TEST(LocalBlockCorrectionTest, OnSomeNodesItZeroesTheirResidualAndKeepsItZsResidual) {
  const SmallSystem system = MakeSystem();
  const std::vector<int> some = {7, 3, 12};
  LocalBlockCorrection local;
  ASSERT_TRUE(local.Compute(system.model->pattern, system.values, some));
  ASSERT_EQ(local.dofs().size(), 9u);
  const int n = system.model->num_dofs();
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, 1.0, -3.0);
  Eigen::VectorXd z = Eigen::VectorXd::LinSpaced(n, 0.0, 0.01);
  Eigen::VectorXd r = b - system.dense * z;
  const Eigen::VectorXd z_before = z;
  local.Apply(r, z);
  EXPECT_LT((r - (b - system.dense * z)).norm(), 1e-12 * b.norm());  // r is still z's residual
  for (int node : some) EXPECT_LT(r.segment<3>(3 * node).norm(), 1e-12 * b.norm()) << node;
  for (int i = 0; i < n; ++i) {  // z moved on those nodes only
    if (i / 3 != 7 && i / 3 != 3 && i / 3 != 12) {
      EXPECT_EQ(z[i], z_before[i]) << i;
    }
  }
  EXPECT_GT((z - z_before).norm(), 1e-6);

  // ApplyAfter: the same correction from the residual before c was added to z.
  const Eigen::VectorXd c = Eigen::VectorXd::LinSpaced(n, -0.02, 0.03);
  Eigen::VectorXd z_after = z + c, z_apply = z + c, r_apply = r - system.dense * c;
  local.ApplyAfter(r, c, z_after);
  local.Apply(r_apply, z_apply);
  EXPECT_LT((z_after - z_apply).norm(), 1e-12 * z_apply.norm());
}

// From rows given one by one (here the float rows of S, as the shipped solver keeps it) the
// correction is the one of the same values on the pattern, and it keeps no reference to them.
TEST(LocalBlockCorrectionTest, FromARowSourceItIsTheCorrectionOfThoseValues) {
  if (!FloatBlockRows::available()) GTEST_SKIP() << "no AVX2 + FMA (or VESICA_FEM_ELEMENT_KERNEL=scalar)";
  const SmallSystem system = MakeSystem();
  const FemModel& m = *system.model;
  const Eigen::VectorXd rounded = system.values.cast<float>().cast<double>();
  const std::vector<int> some = {7, 3, 12, 0};
  LocalBlockCorrection from_pattern, from_rows;
  ASSERT_TRUE(from_pattern.Compute(m.pattern, rounded, some));
  {
    FloatBlockRows rows;
    rows.Update(m.pattern, system.values);
    ASSERT_TRUE(from_rows.Compute(
        m.num_dofs(),
        [&](int dof, std::vector<int>& columns, std::vector<double>& values) { rows.AppendRow(dof, columns, values); },
        some));
  }  // the rows are gone
  EXPECT_EQ(from_rows.dofs(), from_pattern.dofs());
  const int n = m.num_dofs();
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, 1.0, -3.0);
  Eigen::VectorXd z_pattern = Eigen::VectorXd::LinSpaced(n, 0.0, 0.01), z_rows = z_pattern;
  Eigen::VectorXd r_pattern = b - system.dense * z_pattern, r_rows = r_pattern;
  from_pattern.Apply(r_pattern, z_pattern);
  from_rows.Apply(r_rows, z_rows);
  EXPECT_LT((z_rows - z_pattern).norm(), 1e-14 * z_pattern.norm());
  EXPECT_LT((r_rows - r_pattern).norm(), 1e-14 * r_pattern.norm());
  const Eigen::VectorXd c = Eigen::VectorXd::LinSpaced(n, -0.02, 0.03);
  from_pattern.ApplyAfter(r_pattern, c, z_pattern);
  from_rows.ApplyAfter(r_rows, c, z_rows);
  EXPECT_LT((z_rows - z_pattern).norm(), 1e-14 * z_pattern.norm());
  // And not the correction of the unrounded values: the rows' values were used.
  LocalBlockCorrection exact;
  ASSERT_TRUE(exact.Compute(m.pattern, system.values, some));
  Eigen::VectorXd z_exact = Eigen::VectorXd::LinSpaced(n, 0.0, 0.01), r_exact = b - system.dense * z_exact;
  Eigen::VectorXd z_first = Eigen::VectorXd::LinSpaced(n, 0.0, 0.01), r_first = r_exact;
  exact.Apply(r_exact, z_exact);
  from_rows.Apply(r_first, z_first);
  EXPECT_GT((z_first - z_exact).norm(), 1e-12 * z_exact.norm());
}

TEST(LocalBlockCorrectionTest, RefusesABlockThatIsNotPositiveDefinite) {
  SmallSystem system = MakeSystem();
  system.values[system.model->pattern.diagonal_slot[3 * 5 + 1]] = -1.0;
  LocalBlockCorrection local;
  EXPECT_FALSE(local.Compute(system.model->pattern, system.values, {4, 5}));
  EXPECT_TRUE(local.empty());
  Eigen::VectorXd r = Eigen::VectorXd::Ones(system.model->num_dofs()), z = Eigen::VectorXd::Zero(r.size());
  local.Apply(r, z);  // empty: nothing
  EXPECT_TRUE(z.isZero(0.0));
  EXPECT_TRUE(local.Compute(system.model->pattern, system.values, {4, 6}));  // node 5 left out
}

TEST(LocalBlockCorrectionTest, LargestSpreadNodesLargestFirstTiesByIndexZerosLeftOut) {
  const std::vector<double> spread = {0.0, 0.3, 0.1, 0.3, 0.0, 0.5, 0.2};
  EXPECT_EQ(LargestSpreadNodes(spread, 3), (std::vector<int>{5, 1, 3}));
  EXPECT_EQ(LargestSpreadNodes(spread, 2), (std::vector<int>{5, 1}));
  EXPECT_EQ(LargestSpreadNodes(spread, 100), (std::vector<int>{5, 1, 3, 6, 2}));
  EXPECT_TRUE(LargestSpreadNodes(spread, 0).empty());
  EXPECT_TRUE(LargestSpreadNodes(std::vector<double>(4, 0.0), 3).empty());
}

}  // namespace
}  // namespace vesica::physics
