#include "physics/scene/dissection_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

#include "physics/bem/tool_contact_load.h"
#include "physics/scene/haptic_force_renderer.h"
#include "physics/tissue/spring_forces.h"
#include "tests/scene/synthetic_dissection.h"

namespace vesica::physics {
namespace {

using testing::kGallbladderBottomInsertion;

class DissectionSceneTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { model_ = BuildDissectionModel(testing::SyntheticDissectionInputs()); }
  static void TearDownTestSuite() { model_.reset(); }

  static std::array<InstrumentPose, 2> Poses(double grasper_insertion, double hook_insertion, double jaw = 0.5) {
    std::array<InstrumentPose, 2> p{};
    p[0].insertion_m = grasper_insertion;
    p[0].jaw_angle_rad = jaw;
    p[1].insertion_m = hook_insertion;
    return p;
  }
  // Sum over the gallbladder of the spring forces at the scene's current state.
  static Eigen::Vector3d SpringForceOnGallbladder(const DissectionScene& scene) {
    TetrahedralMesh gb = scene.model().gallbladder->rest_mesh;
    gb.vertices = scene.gallbladder().CurrentPositions();
    TriangleMesh liver = scene.model().liver->rest_surface;
    liver.vertices = scene.liver_positions();
    const TissueNodalForces f =
        ComputeTissueForces(scene.tissue(), gb, Vertices::Zero(gb.num_vertices(), 3), liver,
                            Vertices::Zero(liver.num_vertices(), 3), scene.model().settings.springs);
    return f.gallbladder.colwise().sum().transpose();
  }

  static std::shared_ptr<const DissectionModel> model_;
};
std::shared_ptr<const DissectionModel> DissectionSceneTest::model_;

constexpr double kAway = 0.02;  // insertion that keeps a tool 38 mm below the gallbladder

TEST_F(DissectionSceneTest, ModelHasOneSpringPerTopVertexOfTheGallbladder) {
  // 4 x 4 top vertices of the 3 x 2 x 3-cell box, each 2 mm under the liver's bed face.
  ASSERT_EQ(model_->tissue.springs.size(), 16u);
  const TetrahedralMesh& gb = model_->gallbladder->rest_mesh;
  const TriangleMesh& liver = model_->liver->rest_surface;
  for (const TissueSpring& s : model_->tissue.springs) {
    EXPECT_NEAR(s.rest_length, 0.002, 1e-12);
    const Eigen::Vector3d p = gb.vertices.row(s.gallbladder_vertex).transpose();
    EXPECT_NEAR(p.y(), -0.002, 1e-12);
    EXPECT_TRUE(LiverEnd(s, liver.vertices, liver.triangles).isApprox(p + Eigen::Vector3d(0, 0.002, 0), 1e-12));
    EXPECT_NEAR(s.liver_weights.sum(), 1.0, 1e-12);
    EXPECT_GE(s.liver_weights.minCoeff(), 0.0);
  }
  EXPECT_TRUE(model_->toward_liver.isApprox(Eigen::Vector3d::UnitY(), 0.1));
}

TEST_F(DissectionSceneTest, SceneAtRestStaysAtRest) {
  DissectionScene scene(model_);
  const Vertices rest = scene.gallbladder().CurrentPositions();
  for (int k = 0; k < 50; ++k) {
    const DissectionStepReport r = scene.Step(Poses(kAway, kAway));
    ASSERT_TRUE(r.gallbladder_accepted) << r.rejection_reason;
    EXPECT_EQ(r.constraint_rows, 0);
  }
  EXPECT_LT((scene.gallbladder().CurrentPositions() - rest).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((scene.liver_positions() - model_->liver->rest_surface.vertices).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT(scene.Energy(), 1e-15);
  EXPECT_FALSE(scene.haptic_frame(0).active);
  EXPECT_NEAR(scene.time_s(), 50 * model_->settings.time_step_s, 1e-12);
}

TEST_F(DissectionSceneTest, PushingHookStaysOnTheGallbladderSurface) {
  DissectionScene scene(model_);
  // Press 1 mm into the bottom face over 0.3 s (the 2 mm springs shorten: the push is resisted
  // by the springs, the gallbladder's inertia and its local stiffness).
  DissectionStepReport r;
  for (int k = 0; k <= 60; ++k) {
    r = scene.Step(Poses(kAway, kGallbladderBottomInsertion - 0.007 + k * 0.008 / 60.0));
    ASSERT_TRUE(r.gallbladder_accepted) << r.rejection_reason;
  }
  // The hook stays on the surface it pushed up (no penetration beyond the solver tolerance).
  EXPECT_EQ(r.touches[1].surface, TouchedSurface::kGallbladder);
  EXPECT_NEAR(r.touches[1].gap_m, 0.0, 1e-6);
  const double lift =
      (scene.gallbladder().CurrentPositions() - model_->gallbladder->rest_mesh.vertices).col(1).maxCoeff();
  EXPECT_GT(lift, 0.0005);
  // The tissue pushes back along -y (the bottom face's outward normal).
  const Eigen::Vector3d f = r.tool_force_N[1];
  EXPECT_LT(f.y(), -0.01);
  EXPECT_LT(std::hypot(f.x(), f.z()), 0.1 * std::abs(f.y()));
  // The frame published for the device loop carries the same force and a positive stiffness along y.
  const HapticContactFrame& frame = scene.haptic_frame(1);
  ASSERT_TRUE(frame.active);
  EXPECT_TRUE(frame.unilateral);
  EXPECT_TRUE(frame.f_Tool_W.isApprox(f, 1e-12));
  EXPECT_GT(frame.stiffness_N_per_m(1, 1), 0.0);
  // The normal of the surface as it moved this step: within a few degrees of the rest face's.
  EXPECT_GT(frame.normal_W.dot(-Eigen::Vector3d::UnitY()), std::cos(0.1));
}

TEST_F(DissectionSceneTest, PushingTheLiverDeformsItAsTheBemSolutionForTheContactForce) {
  // The hook, aimed past the gallbladder at the bed face, presses 1 mm into the liver. The
  // springs are cut first, so the contact is the liver's only load.
  DissectionScene scene(model_);
  for (int s = 0; s < static_cast<int>(scene.tissue().springs.size()); ++s) scene.CutSpring(s);
  const InstrumentMount& hook = model_->instruments[1];
  const Eigen::Vector3d target(0.03, 0.0, 0.004);  // on the bed face, clear of the gallbladder
  const double reach = (target - hook.p_RemoteCentre_W).norm();
  std::array<InstrumentPose, 2> p = Poses(kAway, 0.0);
  DissectionStepReport r;
  for (int k = 0; k <= 20; ++k) {
    p[1] = AimAt(hook.p_RemoteCentre_W, target, reach - 0.004 + k * 0.005 / 20.0, hook.reference_direction_W);
    r = scene.Step(p);
  }
  ASSERT_EQ(r.touches[1].surface, TouchedSurface::kLiver);
  EXPECT_NEAR(r.touches[1].gap_m, 0.0, 1e-9);
  const Eigen::Vector3d f = r.tool_force_N[1];
  EXPECT_LT(f.y(), 0.0);
  // Independent check: the liver's shape is the capacitance solve for the contact force spread
  // over the hook's footprint (a rigid punch's traction on a disc around the touch point, issue
  // 37), the force being along the surface's normal there.
  const BemModel& liver = *model_->liver;
  const BemContactLoad load = MakeToolContactLoad(liver, r.touches[1].triangle, r.touches[1].weights, f.normalized(),
                                                  model_->settings.hook_liver_footprint_radius_m);
  std::vector<int> nodes;
  std::vector<Eigen::Vector3d> tractions;
  for (size_t j = 0; j < load.nodes.size(); ++j) {
    if (liver.layout.free_index(load.nodes[j]) < 0) continue;
    nodes.push_back(load.nodes[j]);
    tractions.push_back(-f * load.traction_per_N(static_cast<Eigen::Index>(j)));
  }
  EXPECT_GE(nodes.size(), 3u);
  Vertices t(static_cast<Eigen::Index>(nodes.size()), 3);
  for (size_t k = 0; k < nodes.size(); ++k) t.row(static_cast<Eigen::Index>(k)) = tractions[k].transpose();
  BemCapacitanceSolver solver(liver);
  solver.SetAppliedTractions(nodes, t);
  BemSolution reference;
  solver.Solve(Vertices(0, 3), reference);
  const Vertices u = scene.liver_positions() - liver.rest_surface.vertices;
  EXPECT_LT((u - reference.displacement_m).cwiseAbs().maxCoeff(),
            1e-9 * reference.displacement_m.cwiseAbs().maxCoeff());
  // 1 mm of indentation of a 170 kPa liver under a 3 mm tip: tenths of a newton.
  EXPECT_GT(f.norm(), 0.05);
  EXPECT_LT(f.norm(), 5.0);
}

TEST_F(DissectionSceneTest, BackingOffReleasesTheContact) {
  DissectionScene scene(model_);
  for (int k = 0; k < 100; ++k) scene.Step(Poses(kAway, kGallbladderBottomInsertion - 0.002 + std::min(k, 50) * 1e-4));
  ASSERT_TRUE(scene.haptic_frame(1).active);
  DissectionStepReport r;
  for (int k = 0; k < 100; ++k) r = scene.Step(Poses(kAway, kGallbladderBottomInsertion - 0.01));
  EXPECT_FALSE(scene.haptic_frame(1).active);
  EXPECT_EQ(r.tool_force_N[1], Eigen::Vector3d::Zero());
  EXPECT_EQ(r.touches[1].surface, TouchedSurface::kNone);
}

// Approach the bottom face with the jaw open, stop 1 mm short, close: the grasp takes hold.
void GraspBottom(DissectionScene& scene, double hook_insertion) {
  std::array<InstrumentPose, 2> p{};
  p[0].jaw_angle_rad = 0.5;
  p[1].insertion_m = hook_insertion;
  for (int k = 0; k < 40; ++k) {
    p[0].insertion_m = kGallbladderBottomInsertion - 0.001 - 0.02 * (1.0 - k / 39.0);
    scene.Step(p);
  }
  p[0].jaw_angle_rad = 0.0;
  scene.Step(p);
}

TEST_F(DissectionSceneTest, GraspHoldsWithinTheSlipDistanceAndFollowsTheJaw) {
  DissectionScene scene(model_);
  GraspBottom(scene, kAway);
  ASSERT_EQ(scene.grasp().state(), GraspStateMachine::State::kHolding);
  ASSERT_FALSE(scene.grasp().points().empty());
  // Pull down 6 mm (less than the 10 mm slip distance) at 12 mm/s and hold.
  std::array<InstrumentPose, 2> p = Poses(kGallbladderBottomInsertion - 0.001, kAway, 0.0);
  DissectionStepReport r;
  for (int k = 0; k < 300; ++k) {
    p[0].insertion_m = kGallbladderBottomInsertion - 0.001 - 0.006 * std::min(1.0, k / 100.0);
    r = scene.Step(p);
    ASSERT_TRUE(r.gallbladder_accepted) << r.rejection_reason;
    ASSERT_EQ(r.grasp.slipped, 0) << "step " << k;
  }
  EXPECT_EQ(scene.grasp().state(), GraspStateMachine::State::kHolding);
  EXPECT_EQ(scene.grasp().total_slips(), 0);
  // The gallbladder hangs from the jaw: the tool feels it pulled up (+y), the grasp frame pulls.
  EXPECT_GT(r.tool_force_N[0].y(), 0.01);
  EXPECT_FALSE(scene.haptic_frame(0).unilateral);
  // The jaw holds its footprint's mean at the tip within the grasp's soft compliance and the
  // tissue's give under the jaw (the subgrid compliance, adopted by now) times the force.
  const GraspJaw& jaw = scene.grasp_jaw();
  ASSERT_TRUE(jaw.holding());
  ASSERT_TRUE(jaw.computed().has_value()) << jaw.failure();
  const Vertices volume = scene.gallbladder().CurrentPositions();
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < jaw.nodes().size(); ++i) mean += jaw.weights()[i] * volume.row(jaw.nodes()[i]).transpose();
  // Exactly: the step's correction moves the mean by W lambda, leaving the series part as the gap.
  const Eigen::Matrix3d give =
      model_->settings.grasp_compliance_m_per_N * Eigen::Matrix3d::Identity() + jaw.computed()->subgrid_m_per_N;
  EXPECT_GT(jaw.computed()->subgrid_m_per_N.norm(), 0.1 * model_->settings.grasp_compliance_m_per_N);
  EXPECT_LT((mean - scene.tool_tip(0) - give * r.tool_force_N[0]).norm(), 1e-9)
      << (mean - scene.tool_tip(0)).transpose() << " vs " << (give * r.tool_force_N[0]).transpose();
  // The touched points stay within the slip distance of the jaw.
  const TetBoundary& b = model_->gallbladder_boundary;
  const Vertices x = scene.gallbladder_surface_positions();
  for (const GraspPoint& g : scene.grasp().points()) {
    Eigen::Vector3d q = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) q += g.weights[k] * x.row(b.surface.triangles(g.triangle, k)).transpose();
    EXPECT_LT((q - scene.tool_tip(0)).norm(), model_->settings.grasp.slip_distance);
  }
  // Opening the jaw releases.
  p[0].jaw_angle_rad = 0.5;
  r = scene.Step(p);
  EXPECT_TRUE(r.grasp.released);
  EXPECT_EQ(scene.grasp().state(), GraspStateMachine::State::kOpen);
}

TEST_F(DissectionSceneTest, JerkBeyondTheSlipDistanceSlips) {
  DissectionScene scene(model_);
  GraspBottom(scene, kAway);
  ASSERT_EQ(scene.grasp().state(), GraspStateMachine::State::kHolding);
  const int held = static_cast<int>(scene.grasp().points().size());
  // 15 mm down in one 5 ms step: the tissue cannot follow, the jaw is > 10 mm from its points.
  const DissectionStepReport r = scene.Step(Poses(kGallbladderBottomInsertion - 0.016, kAway, 0.0));
  EXPECT_EQ(r.grasp.slipped, held);
  EXPECT_EQ(scene.grasp().total_slips(), held);
  EXPECT_EQ(scene.grasp().state(), GraspStateMachine::State::kClosedEmpty);
  EXPECT_EQ(r.tool_force_N[0], Eigen::Vector3d::Zero());
}

TEST_F(DissectionSceneTest, RenderedForceIsContinuousAcrossPhysicsSteps) {
  // The hook presses into the gallbladder at 10 mm/s; the device loop renders at 1 kHz from the
  // latest frame. Holding each frame's force (zero-order hold) jumps at every physics step; the
  // renderer's change at a step boundary must be no larger than its change between boundaries.
  DissectionScene scene(model_);
  const double h = model_->settings.time_step_s, v = 0.01, dt = 0.001;
  const double start = kGallbladderBottomInsertion - 0.001;
  const Eigen::Vector3d rc = model_->instruments[1].p_RemoteCentre_W;
  HapticForceRenderer renderer(h);
  double max_boundary = 0, max_interior = 0, max_hold_jump = 0, max_force = 0;
  Eigen::Vector3d last = Eigen::Vector3d::Zero(), last_held = Eigen::Vector3d::Zero();
  for (int step = 0; step < 60; ++step) {
    scene.Step(Poses(kAway, start + v * step * h));
    const HapticContactFrame frame = scene.haptic_frame(1);
    for (int tick = 0; tick < 5; ++tick) {
      const double t = step * h + tick * dt;
      const Eigen::Vector3d p = rc + Eigen::Vector3d(0, start + v * t, 0);
      if (tick == 0) renderer.Update(frame, p, t);
      const Eigen::Vector3d f = renderer.Force(p, t);
      if (step >= 25) {  // well into the contact: nothing new touches
        double& slot = tick == 0 ? max_boundary : max_interior;
        slot = std::max(slot, (f - last).norm());
        if (tick == 0) max_hold_jump = std::max(max_hold_jump, (frame.f_Tool_W - last_held).norm());
      }
      last = f;
      last_held = frame.f_Tool_W;
      max_force = std::max(max_force, f.norm());
    }
  }
  EXPECT_GT(max_force, 0.03);
  ASSERT_GT(max_hold_jump, 0.0);
  // Stated bound (docs/scene.md): a physics step changes the rendered force no more than a
  // 1 ms tick inside a step does (plus 0.1 mN), and less than a third of the zero-order hold's jump.
  EXPECT_LE(max_boundary, max_interior + 1e-4)
      << "boundary " << max_boundary << " N, interior " << max_interior << " N, hold " << max_hold_jump << " N";
  EXPECT_LT(max_boundary, max_hold_jump / 3)
      << "boundary " << max_boundary << " N, interior " << max_interior << " N, hold " << max_hold_jump << " N";
  std::cout << "boundary " << max_boundary << " N, interior " << max_interior << " N, hold " << max_hold_jump
            << " N, max " << max_force << "\n";
}

TEST_F(DissectionSceneTest, CuttingEverySpringFreesTheGallbladder) {
  DissectionScene scene(model_);
  ASSERT_FALSE(scene.gallbladder_free());
  const int n = static_cast<int>(scene.tissue().springs.size());
  for (int s = 0; s < n; ++s) {
    EXPECT_FALSE(scene.gallbladder_free());
    scene.CutSpring(s);
    scene.Step(Poses(kAway, kAway));
  }
  EXPECT_TRUE(scene.gallbladder_free());
  EXPECT_EQ(scene.tissue().num_alive(), 0);
  for (int k = 0; k < 40; ++k) ASSERT_TRUE(scene.Step(Poses(kAway, kAway)).gallbladder_accepted);
  EXPECT_TRUE(scene.gallbladder().CurrentPositions().allFinite());
  EXPECT_THROW(scene.CutSpring(n), std::out_of_range);
}

TEST_F(DissectionSceneTest, SameCommandsGiveBitIdenticalStates) {
  auto run = [&] {
    DissectionScene scene(model_);
    GraspBottom(scene, kAway);
    for (int k = 0; k < 60; ++k) {
      scene.Step(
          Poses(kGallbladderBottomInsertion - 0.001 - 1e-4 * k, kGallbladderBottomInsertion - 0.002 + 1e-4 * k, 0.0));
      if (k == 30) scene.CutSpring(3);
    }
    return std::make_pair(scene.gallbladder().CurrentPositions(), scene.liver_positions());
  };
  const auto a = run();
  const auto b = run();
  EXPECT_TRUE((a.first.array() == b.first.array()).all());
  EXPECT_TRUE((a.second.array() == b.second.array()).all());
}

TEST_F(DissectionSceneTest, BadPoseIsRejectedWithoutChangingTheState) {
  DissectionScene scene(model_);
  scene.Step(Poses(kAway, kAway));
  const Vertices before = scene.gallbladder().CurrentPositions();
  auto poses = Poses(kAway, kAway);
  poses[1].yaw_rad = std::numeric_limits<double>::quiet_NaN();
  try {
    scene.Step(poses);
    FAIL() << "a NaN pose was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("instrument 1"), std::string::npos) << e.what();
  }
  poses = Poses(-0.01, kAway);
  EXPECT_THROW(scene.Step(poses), std::invalid_argument);
  EXPECT_EQ(scene.steps(), 1);
  EXPECT_TRUE((scene.gallbladder().CurrentPositions().array() == before.array()).all());
}

TEST(DissectionModelTest, BadSettingsAndMissingBedAreNamed) {
  DissectionModelInputs in = testing::SyntheticDissectionInputs();
  in.settings.time_step_s = 0;
  try {
    BuildDissectionModel(in);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("time_step_s"), std::string::npos) << e.what();
  }
  in = testing::SyntheticDissectionInputs();
  in.settings.compliance_adopt_steps = in.settings.compliance_refresh_steps;  // would overlap the next refresh
  try {
    BuildDissectionModel(in);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("compliance_adopt_steps"), std::string::npos) << e.what();
  }
  // The grasp's jaw (issue 37), each field by name.
  const auto jaw_field_named = [](const std::string& field, const std::function<void(DissectionSettings&)>& spoil) {
    DissectionModelInputs bad = testing::SyntheticDissectionInputs();
    spoil(bad.settings);
    try {
      BuildDissectionModel(bad);
      ADD_FAILURE() << field;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  jaw_field_named("grasp_jaw_length_m", [](DissectionSettings& s) { s.grasp_jaw_length_m = 0; });
  jaw_field_named("grasp_jaw_width_m", [](DissectionSettings& s) { s.grasp_jaw_width_m = std::nan(""); });
  jaw_field_named("grasp_subgrid_patch_radius_m", [](DissectionSettings& s) { s.grasp_subgrid_patch_radius_m = -1; });
  jaw_field_named("grasp_subgrid_adopt_steps", [](DissectionSettings& s) { s.grasp_subgrid_adopt_steps = -1; });
  jaw_field_named("grasp_subgrid_ramp_steps", [](DissectionSettings& s) { s.grasp_subgrid_ramp_steps = 0; });
  in = testing::SyntheticDissectionInputs();
  in.liver_surface.vertex_labels = in.liver_surface.vertex_labels.unaryExpr([](int l) { return l & kLabelFixed; });
  EXPECT_THROW(BuildDissectionModel(in), std::invalid_argument);
  in = testing::SyntheticDissectionInputs();
  in.gallbladder_mesh.vertices.col(1).array() -= 0.05;  // 52 mm under the bed: no spring reaches
  try {
    BuildDissectionModel(in);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("synthetic gallbladder box"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vesica::physics

namespace vesica::physics {
namespace {

TEST(DissectionSceneSolverTest, StepReportCarriesTheGallbladderSolversIterationsAndResidual) {
  DissectionModelInputs in = testing::SyntheticDissectionInputs();
  in.gallbladder.solver = LinearSolverKind::kPcg;
  in.settings.gravity_m_per_s2 = Eigen::Vector3d(0, -9.81, 0);  // every step has work to do
  DissectionScene scene(BuildDissectionModel(in));
  std::array<InstrumentPose, 2> away{};
  away[0].insertion_m = away[1].insertion_m = 0.02;
  const DissectionStepReport r = scene.Step(away);
  ASSERT_TRUE(r.gallbladder_accepted) << r.rejection_reason;
  EXPECT_GT(r.gallbladder_solver_iterations, 0);
  EXPECT_LE(r.gallbladder_solver_iterations, in.gallbladder.pcg_max_iterations);
  EXPECT_GE(r.gallbladder_relative_residual, 0.0);
  EXPECT_LT(r.gallbladder_relative_residual, 1.0);
}

}  // namespace
}  // namespace vesica::physics
