#include "physics/scene/grasp_jaw.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <memory>

#include "physics/mesh/primitives.h"
#include "physics/scene/jaw_press_subgrid.h"

namespace vesica::physics {
namespace {

// A 60 x 60 x 30 mm slab of gallbladder tissue on 5 mm cells; the jaw closes at the centre of its
// top face (z = 30 mm), the shaft coming down 30 degrees off vertical along +x.
struct Slab {
  std::shared_ptr<const FemModel> body;
  TetBoundary boundary;
  int top_triangle = -1;
  Eigen::Vector3d weights = Eigen::Vector3d::Constant(1.0 / 3.0);
};

Slab MakeSlab() {
  Slab s;
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.06, 0.06, 0.03}, {12, 12, 6});
  FemSettings settings;
  settings.body_name = "slab";
  settings.material = {2300.0, 0.45, 1000.0};
  s.body = std::make_shared<const FemModel>(BuildFemModel(mesh, settings, {{0, {true, true, true}}}));
  s.boundary = ExtractBoundary(mesh);
  double best = 1e9;
  for (int f = 0; f < s.boundary.surface.num_triangles(); ++f) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k)
      c += s.boundary.surface.vertices.row(s.boundary.surface.triangles(f, k)).transpose() / 3;
    const double d = (c - Eigen::Vector3d(0.03, 0.03, 0.03)).norm();
    if (d < best) best = d, s.top_triangle = f;
  }
  return s;
}

const Eigen::Vector3d kShaft = Eigen::Vector3d(std::sin(0.52), 0.0, -std::cos(0.52));

TEST(JawFootprintAtTest, LiesOnTheTriangleAlongTheShaft) {
  const Slab slab = MakeSlab();
  const auto jaw = JawFootprintAt(slab.boundary.surface, slab.top_triangle, slab.weights, kShaft, 0.010, 0.005);
  ASSERT_TRUE(jaw.has_value());
  EXPECT_NEAR(jaw->centre_m.z(), 0.03, 1e-12);
  EXPECT_TRUE(jaw->normal.isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
  EXPECT_TRUE(jaw->long_axis.isApprox(Eigen::Vector3d::UnitX(), 1e-12));
  // A shaft square to the face leaves the turn free but still in the face.
  const auto square =
      JawFootprintAt(slab.boundary.surface, slab.top_triangle, slab.weights, -Eigen::Vector3d::UnitZ(), 0.010, 0.005);
  ASSERT_TRUE(square.has_value());
  EXPECT_NEAR(square->long_axis.dot(Eigen::Vector3d::UnitZ()), 0.0, 1e-12);
  EXPECT_FALSE(JawFootprintAt(slab.boundary.surface, -1, slab.weights, kShaft, 0.010, 0.005).has_value());
}

// Zero until the adoption step, then ramped to the computed compliance; the same as computing it
// directly; released: nothing held, zero.
TEST(GraspJawTest, AdoptsTheWorkersComplianceAtAFixedStepAndRampsItIn) {
  const Slab slab = MakeSlab();
  GraspJawSettings settings;
  settings.adopt_steps = 10;
  settings.ramp_steps = 4;
  GraspJaw jaw(slab.body, slab.boundary, settings);
  ASSERT_TRUE(jaw.Take(slab.top_triangle, slab.weights, kShaft, 100));
  ASSERT_TRUE(jaw.holding());
  double sum = 0;
  for (double w : jaw.weights()) sum += w;
  EXPECT_NEAR(sum, 1.0, 1e-12);
  EXPECT_EQ(jaw.nodes().size(), jaw.weights().size());
  for (long step = 100; step < 110; ++step) EXPECT_EQ(jaw.SubgridAt(step), Eigen::Matrix3d::Zero()) << step;
  const Eigen::Matrix3d first = jaw.SubgridAt(110);
  ASSERT_TRUE(jaw.computed().has_value()) << jaw.failure();
  const Eigen::Matrix3d full = jaw.computed()->subgrid_m_per_N;
  EXPECT_TRUE(first.isApprox(0.25 * full, 1e-14));
  EXPECT_TRUE(jaw.SubgridAt(112).isApprox(0.75 * full, 1e-14));
  EXPECT_EQ(jaw.SubgridAt(113), full);
  EXPECT_EQ(jaw.SubgridAt(500), full);
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(full).eigenvalues().maxCoeff(), 0.0);
  // The same jaw computed directly.
  const auto at = JawFootprintAt(slab.boundary.surface, slab.top_triangle, slab.weights, kShaft, 0.010, 0.005);
  JawSubgridSettings direct;
  direct.patch_radius_m = settings.patch_radius_m;
  EXPECT_EQ(ComputeJawSubgridCompliance(slab.body->rest_mesh, slab.boundary, slab.body->settings.material, *at, direct)
                .subgrid_m_per_N,
            full);
  jaw.Release();
  EXPECT_FALSE(jaw.holding());
  EXPECT_EQ(jaw.SubgridAt(600), Eigen::Matrix3d::Zero());
  // Released before adoption, then taken again: the abandoned worker does not leak into the new grasp.
  ASSERT_TRUE(jaw.Take(slab.top_triangle, slab.weights, kShaft, 700));
  jaw.Release();
  ASSERT_TRUE(jaw.Take(slab.top_triangle, slab.weights, kShaft, 702));
  EXPECT_EQ(jaw.SubgridAt(711), Eigen::Matrix3d::Zero());
  EXPECT_EQ(jaw.SubgridAt(715), full);
}

// A patch that is the whole body has nothing to hold: the jaw stays the footprint (zero subgrid)
// and says why.
TEST(GraspJawTest, AFailedWorkerLeavesTheFootprintAndSaysWhy) {
  const Slab slab = MakeSlab();
  GraspJawSettings settings;
  settings.patch_radius_m = 1.0;
  settings.adopt_steps = 0;  // computed within the step
  GraspJaw jaw(slab.body, slab.boundary, settings);
  ASSERT_TRUE(jaw.Take(slab.top_triangle, slab.weights, kShaft, 5));
  EXPECT_EQ(jaw.SubgridAt(5), Eigen::Matrix3d::Zero());
  EXPECT_FALSE(jaw.computed().has_value());
  EXPECT_NE(jaw.failure().find("whole body"), std::string::npos) << jaw.failure();
}

// One vertex at a time: zero until adopted, then kept; a second vertex waits for the first.
TEST(JawPressSubgridTest, KeepsEachVertexsPressComplianceOnceComputed) {
  const Slab slab = MakeSlab();
  const auto boundary = std::make_shared<const TetBoundary>(slab.boundary);
  JawPressSubgrid press(slab.body, boundary, 0.015, 5);
  const auto jaw = JawFootprintAt(slab.boundary.surface, slab.top_triangle, slab.weights, kShaft, 0.010, 0.005);
  const int vertex = slab.boundary.surface.triangles(slab.top_triangle, 0);
  const int other = slab.boundary.surface.triangles(slab.top_triangle, 1);
  EXPECT_EQ(press.At(vertex, *jaw, 0), 0.0);
  EXPECT_EQ(press.At(other, *jaw, 1), 0.0);  // not started: the first is pending
  EXPECT_EQ(press.At(vertex, *jaw, 4), 0.0);
  const double value = press.At(vertex, *jaw, 5);
  JawSubgridSettings direct;
  EXPECT_EQ(value,
            ComputeJawSubgridCompliance(slab.body->rest_mesh, slab.boundary, slab.body->settings.material, *jaw, direct)
                .subgrid_normal_m_per_N);
  EXPECT_GT(value, 0.0);
  EXPECT_EQ(press.known(), 1);
  EXPECT_EQ(press.At(other, *jaw, 6), 0.0);  // now started
  EXPECT_EQ(press.At(vertex, *jaw, 7), value);
  EXPECT_GT(press.At(other, *jaw, 11), 0.0);
  EXPECT_EQ(press.known(), 2);
}

}  // namespace
}  // namespace vesica::physics
