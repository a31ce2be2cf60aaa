// A body outside the scene pulling on gallbladder nodes (DissectionScene::SetOutsideLoad), as
// Calot's tubes pull the neck: the force is a step behind the motion, and the declared stiffness
// in the implicit step is what keeps a stiff outside body stable without moving its equilibrium.

#include <gtest/gtest.h>

#include <stdexcept>

#include "physics/scene/dissection_scene.h"
#include "tests/scene/synthetic_dissection.h"

namespace vesica::physics {
namespace {

constexpr double kAway = 0.02;  // insertion that keeps both tools below the gallbladder

std::array<InstrumentPose, 2> ToolsAway() {
  std::array<InstrumentPose, 2> p{};
  p[0].insertion_m = kAway;
  p[1].insertion_m = kAway;
  return p;
}

// The gallbladder box's bottom face: the nodes an outside body pulls down.
std::vector<int> BottomNodes(const DissectionModel& model) {
  std::vector<int> nodes;
  const Vertices& rest = model.gallbladder->rest_mesh.vertices;
  for (Eigen::Index v = 0; v < rest.rows(); ++v)
    if (rest(v, 1) < testing::kGallbladderBottomY + 1e-9) nodes.push_back(static_cast<int>(v));
  return nodes;
}

Eigen::Vector3d MeanPosition(const DissectionScene& scene, const std::vector<int>& nodes) {
  const Vertices x = scene.gallbladder().CurrentPositions();
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const int v : nodes) mean += x.row(v).transpose();
  return mean / static_cast<double>(nodes.size());
}

struct Settled {
  Eigen::Vector3d mean_m, force_N;
  double max_energy_J = 0, final_energy_J = 0;
  bool all_accepted = true;
};

// An outside spring of stiffness_N_per_m from the nodes' mean to an anchor 5 mm below it at
// rest, its force evaluated at the state before each step (a step behind, as the tubes' is).
Settled RunLaggedSpring(const std::shared_ptr<const DissectionModel>& model, double stiffness_N_per_m,
                        double declared_N_per_m, int steps) {
  DissectionScene scene(model);
  const std::vector<int> nodes = BottomNodes(*model);
  const Eigen::Vector3d anchor = MeanPosition(scene, nodes) - Eigen::Vector3d(0, 0.005, 0);
  scene.SetOutsideLoad(nodes, declared_N_per_m);
  Settled out;
  for (int k = 0; k < steps; ++k) {
    out.force_N = stiffness_N_per_m * (anchor - MeanPosition(scene, nodes));
    scene.SetOutsideLoadForce(out.force_N);
    const DissectionStepReport r = scene.Step(ToolsAway());
    out.all_accepted = out.all_accepted && r.gallbladder_accepted;
    out.max_energy_J = std::max(out.max_energy_J, scene.Energy());
  }
  out.mean_m = MeanPosition(scene, nodes);
  out.final_energy_J = scene.Energy();
  return out;
}

class OutsideLoadTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { model_ = BuildDissectionModel(testing::SyntheticDissectionInputs()); }
  static void TearDownTestSuite() { model_.reset(); }
  static std::shared_ptr<const DissectionModel> model_;
};
std::shared_ptr<const DissectionModel> OutsideLoadTest::model_;

TEST_F(OutsideLoadTest, AStiffLaggedPullSettlesWhereTheBodyBalancesItsForce) {
  constexpr double kStiffness = 5000.0;  // the tubes' coupling spring, N/m
  const Settled coupled = RunLaggedSpring(model_, kStiffness, kStiffness, 2000);
  ASSERT_TRUE(coupled.all_accepted);
  // Settled: the outside spring's force is what the body holds at that displacement.
  ASSERT_GT(coupled.force_N.norm(), 0.01);
  EXPECT_GT(coupled.force_N.normalized().dot(-Eigen::Vector3d::UnitY()), 0.99);
  // The same force held constant with no declared stiffness: the body comes to the same place, so
  // the stiffness in the implicit step does not move the equilibrium.
  DissectionScene plain(model_);
  const std::vector<int> nodes = BottomNodes(*model_);
  plain.SetOutsideLoad(nodes, 0.0);
  plain.SetOutsideLoadForce(coupled.force_N);
  for (int k = 0; k < 2000; ++k) ASSERT_TRUE(plain.Step(ToolsAway()).gallbladder_accepted);
  const Eigen::Vector3d rest_mean = MeanPosition(DissectionScene(model_), nodes);
  const Eigen::Vector3d moved_coupled = coupled.mean_m - rest_mean,
                        moved_plain = MeanPosition(plain, nodes) - rest_mean;
  EXPECT_GT(moved_plain.norm(), 1e-4);
  EXPECT_LT((moved_coupled - moved_plain).norm(), 0.01 * moved_plain.norm());
}

TEST_F(OutsideLoadTest, WithoutItsStiffnessTheSameLaggedPullDoesNotSettle) {
  constexpr double kStiffness = 5000.0;
  const Settled declared = RunLaggedSpring(model_, kStiffness, kStiffness, 400);
  const Settled undeclared = RunLaggedSpring(model_, kStiffness, 0.0, 400);
  std::printf("energy max/final: declared %.3g/%.3g J, undeclared %.3g/%.3g J\n", declared.max_energy_J,
              declared.final_energy_J, undeclared.max_energy_J, undeclared.final_energy_J);
  // Declared: the body never holds more energy than the outside spring had at the start.
  const double spring_energy_J = 0.5 * kStiffness * 0.005 * 0.005;
  EXPECT_LT(declared.max_energy_J, spring_energy_J);
  EXPECT_TRUE(declared.all_accepted);
  // Undeclared: the lagged force pumps energy in without bound (or the steps are refused).
  EXPECT_TRUE(!undeclared.all_accepted || !(undeclared.max_energy_J < 100 * spring_energy_J));
}

TEST_F(OutsideLoadTest, BadNodesStiffnessOrForceAreRefusedByName) {
  DissectionScene scene(model_);
  const int n = model_->gallbladder->num_nodes();
  try {
    scene.SetOutsideLoad({0, n}, 1.0);
    FAIL() << "a node past the last was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("node " + std::to_string(n)), std::string::npos) << e.what();
  }
  EXPECT_THROW(scene.SetOutsideLoad({0}, -1.0), std::invalid_argument);
  EXPECT_THROW(scene.SetOutsideLoad({0}, std::nan("")), std::invalid_argument);
  EXPECT_THROW(scene.SetOutsideLoadForce(Eigen::Vector3d::UnitX()), std::invalid_argument);  // no nodes yet
  scene.SetOutsideLoad({0}, 1.0);
  EXPECT_THROW(scene.SetOutsideLoadForce(Eigen::Vector3d(std::nan(""), 0, 0)), std::invalid_argument);
  // Refused calls changed nothing: the scene steps at rest.
  ASSERT_TRUE(scene.Step(ToolsAway()).gallbladder_accepted);
  EXPECT_LT(scene.Energy(), 1e-15);
}

}  // namespace
}  // namespace vesica::physics
