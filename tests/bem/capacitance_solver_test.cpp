#include "physics/bem/capacitance_solver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "bem_test_support.h"
#include "physics/bem/bem_errors.h"

namespace vesica::physics {
namespace {

using testing::DirectBemSolve;
using testing::LiverLikeEllipsoid;
using testing::NodeCondition;

class CapacitanceSolverTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    mesh_ = new TriangleMesh(LiverLikeEllipsoid(160));
    matrices_ = new BemMatrices(AssembleBemMatrices(*mesh_, LiverMaterial()));
    model_ = new BemModel(PrecomputeBemModel(*mesh_, LiverMaterial(), "liver-like ellipsoid"));
  }
  static void TearDownTestSuite() {
    delete model_;
    delete matrices_;
    delete mesh_;
  }
  static TriangleMesh* mesh_;
  static BemMatrices* matrices_;
  static BemModel* model_;
};
TriangleMesh* CapacitanceSolverTest::mesh_ = nullptr;
BemMatrices* CapacitanceSolverTest::matrices_ = nullptr;
BemModel* CapacitanceSolverTest::model_ = nullptr;

double RelativeDifference(const Vertices& a, const Vertices& b) { return (a - b).norm() / b.norm(); }

// The capacitance update (Sherman-Morrison-Woodbury on the precomputed Green's functions) must
// reproduce a full direct solve of the changed system: contact nodes prescribed, spring tractions
// applied elsewhere, fixed region held.
TEST_F(CapacitanceSolverTest, UpdateEqualsDirectResolveForRandomContactSets) {
  std::mt19937 rng(20261122);
  const std::vector<int>& free_nodes = model_->layout.free_nodes;
  std::uniform_real_distribution<double> displacement(-2e-3, 2e-3), traction(-500.0, 500.0);
  BemCapacitanceSolver solver(*model_);
  for (int s = 1; s <= 20; ++s) {
    std::vector<int> shuffled = free_nodes;
    std::shuffle(shuffled.begin(), shuffled.end(), rng);
    const std::vector<int> contacts(shuffled.begin(), shuffled.begin() + s);
    const std::vector<int> loaded(shuffled.begin() + s, shuffled.begin() + s + 3);
    Vertices u_c(s, 3), t_a(3, 3);
    u_c = u_c.unaryExpr([&](double) { return displacement(rng); });
    t_a = t_a.unaryExpr([&](double) { return traction(rng); });

    solver.SetContactNodes(contacts);
    solver.SetAppliedTractions(loaded, t_a);
    BemSolution cma;
    solver.Solve(u_c, cma);

    std::vector<NodeCondition> condition(static_cast<std::size_t>(mesh_->num_vertices()), NodeCondition::kTraction);
    Vertices known = Vertices::Zero(mesh_->num_vertices(), 3);
    for (int i : model_->layout.fixed_nodes) condition[static_cast<std::size_t>(i)] = NodeCondition::kDisplacement;
    for (int k = 0; k < s; ++k) {
      condition[static_cast<std::size_t>(contacts[static_cast<std::size_t>(k)])] = NodeCondition::kDisplacement;
      known.row(contacts[static_cast<std::size_t>(k)]) = u_c.row(k);
    }
    for (int k = 0; k < 3; ++k) known.row(loaded[static_cast<std::size_t>(k)]) = t_a.row(k);
    const auto [u_direct, t_direct] = DirectBemSolve(*matrices_, condition, known);

    EXPECT_LT(RelativeDifference(cma.displacement_m, u_direct), 1e-8) << s << " contacts";
    EXPECT_LT(RelativeDifference(cma.traction_Pa, t_direct), 1e-8) << s << " contacts";

    // The haptic-rate query agrees with the global solve at the contacts.
    Vertices t_c, f_c;
    solver.ContactTractions(u_c, t_c);
    solver.ContactForces(u_c, f_c);
    for (int k = 0; k < s; ++k) {
      const int node = contacts[static_cast<std::size_t>(k)];
      EXPECT_LT((t_c.row(k) - t_direct.row(node)).norm(), 1e-8 * t_direct.row(node).norm() + 1e-9);
      EXPECT_LT((f_c.row(k) - model_->lumped_area_m2(node) * t_direct.row(node)).norm(),
                1e-8 * model_->lumped_area_m2(node) * t_direct.row(node).norm() + 1e-12);
    }
  }
}

// Pulling a node outward must pull (positive work: t . u > 0 at the contact) and drag its
// neighbours along less than itself; the fixed region stays put.
TEST_F(CapacitanceSolverTest, PullingANodeDoesPositiveWorkAndFixedRegionStays) {
  BemCapacitanceSolver solver(*model_);
  int tip = 0;  // the vertex farthest along +x (opposite the fixed cap)
  mesh_->vertices.col(0).maxCoeff(&tip);
  const std::vector<int> contact{tip};
  solver.SetContactNodes(contact);
  Vertices u_c(1, 3);
  u_c << 5e-3, 0, 0;
  BemSolution solution;
  solver.Solve(u_c, solution);
  EXPECT_GT(solution.traction_Pa.row(tip).dot(u_c.row(0)), 0.0);
  for (int i : model_->layout.fixed_nodes) EXPECT_EQ(solution.displacement_m.row(i).norm(), 0.0);
  for (int i = 0; i < mesh_->num_vertices(); ++i)
    if (i != tip) {
      EXPECT_LT(solution.displacement_m.row(i).norm(), 5e-3 * 1.0001) << i;
    }
  // Linear elasticity: twice the pull gives twice every displacement.
  BemSolution doubled;
  solver.Solve(2.0 * u_c, doubled);
  EXPECT_LT((doubled.displacement_m - 2.0 * solution.displacement_m).norm(),
            1e-12 * solution.displacement_m.norm());
}

TEST_F(CapacitanceSolverTest, RejectsBadContactSetsAndKeepsThePreviousOne) {
  BemCapacitanceSolver solver(*model_);
  const int free_node = model_->layout.free_nodes[5];
  const std::vector<int> good{free_node};
  solver.SetContactNodes(good);
  const std::vector<int> repeated{free_node, model_->layout.free_nodes[7], free_node};
  EXPECT_THROW(solver.SetContactNodes(repeated), SingularSystemError);
  const std::vector<int> fixed{model_->layout.fixed_nodes[0]};
  EXPECT_THROW(solver.SetContactNodes(fixed), BemError);
  const std::vector<int> out_of_range{mesh_->num_vertices()};
  EXPECT_THROW(solver.SetContactNodes(out_of_range), BemError);
  EXPECT_EQ(solver.contact_nodes(), good);
  Vertices wrong_rows(2, 3);
  wrong_rows.setZero();
  BemSolution solution;
  EXPECT_THROW(solver.Solve(wrong_rows, solution), BemError);
  Vertices nan(1, 3);
  nan << std::nan(""), 0, 0;
  EXPECT_THROW(solver.Solve(nan, solution), BemError);
}

}  // namespace
}  // namespace vesica::physics
