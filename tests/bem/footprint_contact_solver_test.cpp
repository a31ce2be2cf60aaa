#include "physics/bem/footprint_contact_solver.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "bem_test_support.h"
#include "physics/bem/bem_errors.h"
#include "physics/bem/tool_contact_load.h"

namespace vesica::physics {
namespace {

using testing::DirectBemSolve;
using testing::LiverLikeEllipsoid;
using testing::NodeCondition;

class FootprintContactSolverTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    mesh_ = new TriangleMesh(LiverLikeEllipsoid(320));
    matrices_ = new BemMatrices(AssembleBemMatrices(*mesh_, LiverMaterial()));
    model_ = new BemModel(PrecomputeBemModel(*mesh_, LiverMaterial(), "liver-like ellipsoid"));
  }
  static void TearDownTestSuite() {
    delete model_;
    delete matrices_;
    delete mesh_;
  }
  // A disc on the free side (x > 0), 15 mm across: several elements.
  static ToolFootprint Disc(double radius_m) {
    int f = 0;
    double best = -1;
    for (int t = 0; t < mesh_->num_triangles(); ++t) {
      const double x = mesh_->vertices(mesh_->triangles(t, 0), 0) + mesh_->vertices(mesh_->triangles(t, 1), 0) +
                       mesh_->vertices(mesh_->triangles(t, 2), 0);
      if (x > best) best = x, f = t;
    }
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) c += mesh_->vertices.row(mesh_->triangles(f, k)).transpose() / 3.0;
    return DiscFootprint(*mesh_, f, c, Eigen::Vector3d::UnitX(), radius_m);
  }
  static TriangleMesh* mesh_;
  static BemMatrices* matrices_;
  static BemModel* model_;
};
TriangleMesh* FootprintContactSolverTest::mesh_ = nullptr;
BemMatrices* FootprintContactSolverTest::matrices_ = nullptr;
BemModel* FootprintContactSolverTest::model_ = nullptr;

// The solver's deformation is the body's response to the modes' tractions: a direct solve of
// H U = G T with those tractions on the free surface and the fixed region held gives the same
// displacements. And the constraint holds: each shape's p-weighted mean displacement is the
// tool's translation (times the shape's resultant).
TEST_F(FootprintContactSolverTest, DeformationIsTheDirectResponseAndMeetsTheConstraint) {
  FootprintOptions options;
  options.shapes = {FootprintShape::kUniform, FootprintShape::kPunch, FootprintShape::kTiltX, FootprintShape::kTiltY};
  const FootprintModes modes = MakeFootprintModes(*mesh_, model_->lumped_area_m2, Disc(0.0075), options);
  BemFootprintSolver solver(*model_);
  solver.SetFootprint(modes);
  const Eigen::Vector3d d(-3e-3, 1e-3, 0.5e-3);
  BemSolution out;
  solver.Solve(d, out);

  std::vector<NodeCondition> condition(static_cast<std::size_t>(mesh_->num_vertices()), NodeCondition::kTraction);
  Vertices known = out.traction_Pa;
  for (int i : model_->layout.fixed_nodes) {
    condition[static_cast<std::size_t>(i)] = NodeCondition::kDisplacement;
    known.row(i).setZero();
  }
  const auto [u, t] = DirectBemSolve(*matrices_, condition, known);
  EXPECT_LT((u - out.displacement_m).norm(), 1e-8 * u.norm());
  EXPECT_LT((t - out.traction_Pa).norm(), 1e-8 * t.norm());

  for (std::size_t s = 0; s < modes.shapes.size(); ++s) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < modes.nodes.size(); ++i)
      mean += modes.load_weights(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(s)) *
              out.displacement_m.row(modes.nodes[i]).transpose();
    EXPECT_LT((mean - modes.resultant(static_cast<Eigen::Index>(s)) * d).norm(), 1e-9 * d.norm()) << "shape " << s;
  }
  // Pushed in (-x, into the body), the tissue is pushed in: the force leans along the push.
  const Eigen::Vector3d force = solver.ContactForce(d);
  EXPECT_GT(force.dot(d), 0.5 * force.norm() * d.norm());
  EXPECT_LT((solver.ContactForce(-2 * d) + 2 * force).norm(), 1e-12 * force.norm());
}

// The scene's path (one punch shape as a constraint row: tool_contact_load.h) is the solver's
// one-shape mode compliance.
TEST_F(FootprintContactSolverTest, SceneLoadComplianceIsThePunchModeCompliance) {
  const ToolFootprint disc = Disc(0.005);
  FootprintOptions options;
  options.shapes = {FootprintShape::kPunch};
  options.subdivision_levels = 2;
  BemFootprintSolver solver(*model_);
  solver.SetFootprint(MakeFootprintModes(*mesh_, model_->lumped_area_m2, disc, options));
  // The same disc through the scene's entry point: the hit triangle and barycentric weights.
  const int f = disc.triangles.front();
  Eigen::Matrix3d x;
  for (int k = 0; k < 3; ++k) x.col(k) = mesh_->vertices.row(mesh_->triangles(f, k)).transpose();
  const Eigen::Vector3d weights = x.colPivHouseholderQr().solve(disc.centre_W);
  const BemContactLoad load = MakeToolContactLoad(*model_, f, weights, disc.normal_W, disc.radius_m);
  const Eigen::Matrix3d c = ContactLoadCompliance(*model_, load, load);
  EXPECT_LT((c - solver.mode_compliance()).norm(), 1e-9 * c.norm());
  Eigen::VectorXd du = Eigen::VectorXd::Zero(3 * mesh_->num_vertices());
  const Eigen::Vector3d force(-1.0, 0.2, 0.0);
  AddContactLoadResponse(*model_, load, force, du);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < load.nodes.size(); ++i)
    mean += load.load_weights(static_cast<Eigen::Index>(i)) * du.segment<3>(3 * load.nodes[i]);
  EXPECT_LT((mean - c * force).norm(), 1e-12 * mean.norm());
  EXPECT_THROW(MakeToolContactLoad(*model_, f, Eigen::Vector3d(0.5, 0.6, 0.1), disc.normal_W, 0.005), BemError);
  EXPECT_THROW(MakeToolContactLoad(*model_, -1, weights, disc.normal_W, 0.005), BemError);
}

TEST_F(FootprintContactSolverTest, BadInputIsRefused) {
  BemFootprintSolver solver(*model_);
  EXPECT_THROW(solver.ContactForce(Eigen::Vector3d::Zero()), BemError);  // no footprint yet
  FootprintModes modes = MakeFootprintModes(*mesh_, model_->lumped_area_m2, Disc(0.005));
  FootprintModes wrong = modes;
  wrong.resultant.resize(1);
  EXPECT_THROW(solver.SetFootprint(wrong), BemError);
  FootprintModes fixed = modes;
  for (int& node : fixed.nodes) node = model_->layout.fixed_nodes.front();
  EXPECT_THROW(solver.SetFootprint(fixed), BemError);
  FootprintModes twice = modes;  // two equal shapes: the mode compliance is singular
  twice.shapes = {FootprintShape::kPunch, FootprintShape::kPunch};
  twice.load_weights = modes.load_weights.col(1).replicate(1, 2);
  twice.traction_per_N = modes.traction_per_N.col(1).replicate(1, 2);
  twice.resultant = Eigen::Vector2d(1, 1);
  EXPECT_THROW(solver.SetFootprint(twice), SingularSystemError);
  solver.SetFootprint(modes);
  EXPECT_THROW(solver.ContactForce(Eigen::Vector3d(std::nan(""), 0, 0)), BemError);
}

}  // namespace
}  // namespace vesica::physics
