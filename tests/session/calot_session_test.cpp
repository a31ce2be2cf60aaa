// Calot's triangle in the dissection session (issue 36): the default scenario with the standard
// triangle added. The neck follows the gallbladder, the clip applier and the scissors act when
// their jaws close across a tube, the hook's pedal burns the fat, the metrics judge it all, a
// clip on the common bile duct ends the case, and the Calot columns reach SessionMetrics.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <chrono>
#include <fstream>
#include <thread>

#include "app/render/scene_meshes.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_session.h"
#include "app/session/dissection_setup.h"
#include "app/session/session_runner.h"
#include "device/input/replay_input.h"
#include "physics/instrument/instrument_pose.h"
#include "physics/tissue/connective_tissue.h"

namespace vesica::app {
namespace {

using calot::StructureKind;
using physics::InstrumentTool;

constexpr int kCysticDuct = 0, kArtery = 1, kCommonBileDuct = 3;

// The committed standard variant: the usual triangle on the default scenario's organs.
std::filesystem::path StandardTriangleScenario() { return DefaultScenarioPath().parent_path() / "calot-standard.toml"; }

class CalotSessionTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scenario_ = new Scenario(LoadScenario(StandardTriangleScenario()));
    model_ = BuildDissectionModelFor(*scenario_, LoadSceneMeshes(*scenario_));
  }
  static void TearDownTestSuite() {
    delete scenario_;
    model_.reset();
  }

  static std::unique_ptr<DissectionSession> NewSession() {
    return std::make_unique<DissectionSession>(model_, DefaultCauteryParams(), CalotSessionSetupFor(*scenario_));
  }

  // The right hand's pose that puts its tip at `target` (m), jaws at `jaw_rad`.
  static physics::InstrumentPose RightTipAt(const Eigen::Vector3d& target, double jaw_rad) {
    const physics::InstrumentMount& mount = model_->instruments[1];
    physics::InstrumentPose pose = physics::AimAt(
        mount.p_RemoteCentre_W, target, (target - mount.p_RemoteCentre_W).norm(), mount.reference_direction_W);
    pose.jaw_angle_rad = jaw_rad;
    return pose;
  }

  // The grasper at rest at its port (out of the field), the right tool at its pose.
  static device::InputFrame Frame(InstrumentTool tool, const physics::InstrumentPose& right, bool pedal = false) {
    device::InputFrame f;
    f.right_tool = tool;
    f.instruments[1].pose = right;
    f.instruments[1].pedal = pedal;
    return f;
  }

  // Brings the open jaws to the tube's point at s (0..1) and closes them there.
  static void CloseJawsOn(DissectionSession& session, InstrumentTool tool, int tube, double s) {
    const auto& tubes = *session.calot_tubes();
    for (int i = 0; i < 2; ++i)
      session.Step(Frame(tool, RightTipAt(tubes.PositionAt(tube, s * tubes.TubeLength_m(tube)), 0.5)));
    session.Step(Frame(tool, RightTipAt(tubes.PositionAt(tube, s * tubes.TubeLength_m(tube)), 0.0)));
  }

  static Scenario* scenario_;
  static std::shared_ptr<const physics::DissectionModel> model_;
};
Scenario* CalotSessionTest::scenario_ = nullptr;
std::shared_ptr<const physics::DissectionModel> CalotSessionTest::model_;

TEST_F(CalotSessionTest, WithoutATriangleThereIsNoCalotStep) {
  DissectionSession session(model_, DefaultCauteryParams());
  session.Step(device::InputFrame{});
  EXPECT_EQ(session.calot_metrics(), nullptr);
  EXPECT_EQ(session.calot_tubes(), nullptr);
  EXPECT_FALSE(session.case_ended());
  EXPECT_FALSE(session.metrics().calot_step);
  EXPECT_FALSE(CalotSessionSetupFor(LoadScenario(DefaultScenarioPath())).has_value());
}

TEST_F(CalotSessionTest, TheNeckFollowsTheGallbladdersNeckNodes) {
  auto session = NewSession();
  const CalotTriangleStep& step = *session->calot_step();
  const Eigen::Vector3d rest_neck = session->calot_tubes()->description().p_Neck_W_m;
  for (int i = 0; i < 100; ++i) session->Step(device::InputFrame{});  // 0.5 s: the gallbladder settles under gravity
  // Independently: the mean displacement of the gallbladder nodes within 8 mm of the neck at rest.
  const physics::Vertices& rest = model_->gallbladder->rest_mesh.vertices;
  const Eigen::VectorXd& u = session->scene().gallbladder().state().displacement_m;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  int n = 0;
  for (Eigen::Index v = 0; v < rest.rows(); ++v)
    if ((rest.row(v).transpose() - rest_neck).norm() <= CalotToolGeometry{}.neck_radius_m) {
      mean += u.segment<3>(3 * v);
      ++n;
    }
  ASSERT_GT(n, 0);
  mean /= n;
  EXPECT_GT(mean.norm(), 1e-4) << "the gallbladder did not move: nothing to follow";
  EXPECT_TRUE(step.neck_W_m().isApprox(rest_neck + mean, 1e-12));
  // The cystic duct's neck end went along (tied by its coupling spring).
  const auto& tubes = *session->calot_tubes();
  const Eigen::Vector3d end = tubes.PositionAt(kCysticDuct, tubes.TubeLength_m(kCysticDuct));
  EXPECT_LT((end - step.neck_W_m()).norm(), 0.5 * mean.norm());
}

TEST_F(CalotSessionTest, TheCameraSeesTheTubesButTheFatHidesThem) {
  auto session = NewSession();
  session->Step(device::InputFrame{});
  const CalotTriangleStep& step = *session->calot_step();
  // The standard scenario's scope looks into the triangle: most of the cystic structures are in
  // its view and not behind the liver or the gallbladder; the fat still hides every tube.
  EXPECT_GT(step.seen_fraction(kCysticDuct), 0.5);
  EXPECT_GT(step.seen_fraction(kArtery), 0.5);
  for (const calot::StructureState& s : step.last_snapshot().structures) EXPECT_EQ(s.visible_fraction, 0.0) << s.name;
  // A camera turned away sees nothing of them.
  CalotSessionSetup away = *CalotSessionSetupFor(*scenario_);
  away.camera.forward_W = -away.camera.forward_W;
  CalotTriangleStep turned(away, session->scene());
  turned.Step(session->scene(), device::InputFrame{}, false);
  for (int t = 0; t < 4; ++t) EXPECT_EQ(turned.seen_fraction(t), 0.0);
  // Seen from beyond the liver (the eye on the line from the duct through the liver's centroid,
  // outside it): the liver hides the duct.
  const auto& tubes = *session->calot_tubes();
  const Eigen::Vector3d duct = tubes.PositionAt(kCysticDuct, 0.5 * tubes.TubeLength_m(kCysticDuct));
  const physics::Vertices& liver = session->scene().liver_positions();
  const Eigen::Vector3d centroid = liver.colwise().mean().transpose();
  const double extent_m = (liver.rowwise() - centroid.transpose()).rowwise().norm().maxCoeff();
  CalotSessionSetup beyond = *CalotSessionSetupFor(*scenario_);
  beyond.camera.forward_W = (duct - centroid).normalized();
  beyond.camera.p_Eye_W_m = centroid - (extent_m + 0.02) * beyond.camera.forward_W;
  beyond.camera.up_W = beyond.camera.forward_W.cross(Eigen::Vector3d::UnitX()).normalized();
  CalotTriangleStep beyond_step(beyond, session->scene());
  beyond_step.Step(session->scene(), device::InputFrame{}, false);
  // The duct's middle is straight ahead, so only the liver can hide it.
  EXPECT_LT(beyond_step.seen_fraction(kCysticDuct), 0.1);
}

TEST_F(CalotSessionTest, TheLowerThirdIsTheCutShareOfTheSpringsNearTheNeck) {
  physics::DissectionScene scene(model_);
  CalotTriangleStep step(*CalotSessionSetupFor(*scenario_), scene);
  // Independently: a spring's gallbladder end (its grown-from vertex, at rest) in the third of the
  // gallbladder's extent along neck -> centroid that is nearest the neck.
  const physics::Vertices& rest = model_->gallbladder->rest_mesh.vertices;
  const Eigen::Vector3d neck = step.tubes().description().p_Neck_W_m;
  const Eigen::Vector3d axis = (rest.colwise().mean().transpose() - neck).normalized();
  const Eigen::VectorXd t = (rest.rowwise() - neck.transpose()) * axis;
  const double third = t.minCoeff() + (t.maxCoeff() - t.minCoeff()) / 3.0;
  std::vector<int> lower, upper;
  for (std::size_t sp = 0; sp < model_->tissue.springs.size(); ++sp) {
    const physics::TissueSpring& spring = model_->tissue.springs[sp];
    const Eigen::Vector3d end = physics::GallbladderEnd(spring, rest, model_->gallbladder->rest_mesh.tets);
    ((end - neck).dot(axis) <= third ? lower : upper).push_back(static_cast<int>(sp));
  }
  ASSERT_GE(lower.size(), 2u);
  ASSERT_FALSE(upper.empty());
  for (const int sp : upper) scene.CutSpring(sp);  // the fundus freed: the lower third untouched
  step.Step(scene, device::InputFrame{}, false);
  EXPECT_EQ(step.last_snapshot().lower_third_separated_fraction, 0.0);
  for (std::size_t k = 0; k < lower.size() / 2; ++k) scene.CutSpring(lower[k]);
  step.Step(scene, device::InputFrame{}, false);
  EXPECT_DOUBLE_EQ(step.last_snapshot().lower_third_separated_fraction,
                   static_cast<double>(lower.size() / 2) / static_cast<double>(lower.size()));
  for (std::size_t k = lower.size() / 2; k < lower.size(); ++k) scene.CutSpring(lower[k]);
  step.Step(scene, device::InputFrame{}, false);
  EXPECT_EQ(step.last_snapshot().lower_third_separated_fraction, 1.0);
}

TEST_F(CalotSessionTest, TheClipApplierClosingAcrossTheCysticDuctPlacesAClip) {
  auto session = NewSession();
  // Closing across nothing places nothing.
  const Eigen::Vector3d away = session->calot_tubes()->PositionAt(kCysticDuct, 0.0) + Eigen::Vector3d(0, 0.03, 0);
  session->Step(Frame(InstrumentTool::kClipApplier, RightTipAt(away, 0.5)));
  session->Step(Frame(InstrumentTool::kClipApplier, RightTipAt(away, 0.0)));
  EXPECT_TRUE(session->calot_tubes()->clips().empty());
  // Closed and moved onto the duct: no closing edge, no clip.
  session->Step(
      Frame(InstrumentTool::kClipApplier, RightTipAt(session->calot_tubes()->PositionAt(kCysticDuct, 0.01), 0.0)));
  EXPECT_TRUE(session->calot_tubes()->clips().empty());

  CloseJawsOn(*session, InstrumentTool::kClipApplier, kCysticDuct, 0.3);
  const auto& tubes = *session->calot_tubes();
  ASSERT_EQ(tubes.clips().size(), 1u);
  EXPECT_EQ(tubes.clips()[0].tube, kCysticDuct);
  EXPECT_NEAR(tubes.clips()[0].s_m / tubes.TubeLength_m(kCysticDuct), 0.3, 0.05);
  const calot::CalotSnapshot& snapshot = session->calot_step()->last_snapshot();
  ASSERT_EQ(snapshot.structures[kCysticDuct].clips_s.size(), 1u);
  EXPECT_DOUBLE_EQ(snapshot.structures[kCysticDuct].clips_s[0], tubes.clips()[0].s_m / tubes.TubeLength_m(kCysticDuct));
  EXPECT_EQ(session->calot_metrics()->ClipsOn(StructureKind::kCysticDuct), 1);
  EXPECT_EQ(session->calot_metrics()->ClipsOn(StructureKind::kCysticArtery), 0);
  // The clip rides on its material point as the duct moves.
  for (int i = 0; i < 20; ++i) session->Step(device::InputFrame{});
  EXPECT_LT((tubes.ClipPosition(0) - tubes.PositionAt(kCysticDuct, tubes.clips()[0].s_m)).norm(), 1e-12);
  const SessionMetrics m = session->metrics();
  EXPECT_TRUE(m.calot_step);
  EXPECT_EQ(m.cystic_duct_clips, 1);
  EXPECT_FALSE(m.cvs_achieved);
  EXPECT_FALSE(session->case_ended());
}

TEST_F(CalotSessionTest, ScissorsCutAndAnUnclippedArteryBleeds) {
  auto session = NewSession();
  CloseJawsOn(*session, InstrumentTool::kScissors, kArtery, 0.5);
  const auto& tubes = *session->calot_tubes();
  ASSERT_EQ(tubes.cuts().size(), 1u);
  EXPECT_EQ(tubes.cuts()[0].tube, kArtery);
  EXPECT_TRUE(tubes.Bleeding());
  const calot::CalotSnapshot& snapshot = session->calot_step()->last_snapshot();
  EXPECT_TRUE(snapshot.structures[kArtery].bleeding);
  ASSERT_EQ(snapshot.structures[kArtery].cuts_s.size(), 1u);
  EXPECT_EQ(session->calot_metrics()->Count(calot::FindingKind::kBleeding), 1);
  for (int i = 0; i < 10; ++i) session->Step(device::InputFrame{});
  EXPECT_EQ(session->metrics().bleeding_events, 1);  // counted once however long it bleeds
  EXPECT_FALSE(session->metrics().cystic_artery_divided_between_clips);
}

TEST_F(CalotSessionTest, TheHooksPedalRemovesFatAndNothingElseDoes) {
  auto session = NewSession();
  const auto& fat = *session->calot_fat();
  // A point in the triangle's slab: its first intact cell.
  int cell = -1;
  for (std::size_t c = 0; c < fat.cells().size() && cell < 0; ++c)
    if (fat.cells()[c].in_triangle && fat.cells()[c].anchor_tube < 0) cell = static_cast<int>(c);
  ASSERT_GE(cell, 0);
  const Eigen::Vector3d target = fat.cell_positions_m()[static_cast<std::size_t>(cell)];
  // Pedal up with the hook, pedal down with the scissors: nothing burns.
  for (int i = 0; i < 40; ++i) session->Step(Frame(InstrumentTool::kCauteryHook, RightTipAt(target, 0), false));
  for (int i = 0; i < 40; ++i) session->Step(Frame(InstrumentTool::kScissors, RightTipAt(target, 0), true));
  EXPECT_EQ(fat.BurntFraction(), 0.0);
  // The hook with its pedal down: the cell (and its neighbours within reach, which share the
  // 30 W) are burnt within 2 s (7.6 J a 2 mm cell; the tubes' sleeve cells move with the tubes,
  // so how many share depends on where the neck holds them).
  for (int i = 0; i < 400 && fat.cells()[static_cast<std::size_t>(cell)].state == physics::calot::FatCellState::kIntact;
       ++i)
    session->Step(Frame(InstrumentTool::kCauteryHook, RightTipAt(target, 0), true));
  EXPECT_EQ(fat.cells()[static_cast<std::size_t>(cell)].state, physics::calot::FatCellState::kBurnt);
  EXPECT_GT(fat.TriangleClearedFraction(), 0.0);
  session->Step(device::InputFrame{});
  EXPECT_DOUBLE_EQ(session->calot_step()->last_snapshot().fat_removed_fraction, fat.TriangleClearedFraction());
}

TEST_F(CalotSessionTest, ThreeClipsThenACutBetweenThemDividesTheArteryDry) {
  auto session = NewSession();
  // Burn fat off the artery's middle first, as a trainee would: the hook on a cell that hides it
  // there, pedal down (1.5 s: a 2 mm cell takes about 0.35 s at 30 W, and the hook pushes the
  // artery and its sleeve as it goes, so this does not bare the artery yet).
  const auto& tubes = *session->calot_tubes();
  const auto& fat = *session->calot_fat();
  const double reach_m = tubes.description().tubes[kArtery].material.outer_radius_m + fat.description().cover_margin_m +
                         0.5 * fat.description().cell_spacing_m;
  const auto next_hiding_cell = [&]() -> int {
    for (std::size_t c = 0; c < fat.cells().size(); ++c) {
      if (fat.cells()[c].state != physics::calot::FatCellState::kIntact) continue;
      for (double s = 0.5; s <= 0.6; s += 0.01)
        if ((fat.cell_positions_m()[c] - tubes.PositionAt(kArtery, s * tubes.TubeLength_m(kArtery))).norm() < reach_m)
          return static_cast<int>(c);
    }
    return -1;
  };
  int steps = 0;
  for (int cell; steps < 300 && (cell = next_hiding_cell()) >= 0; ++steps)
    session->Step(Frame(InstrumentTool::kCauteryHook,
                        RightTipAt(fat.cell_positions_m()[static_cast<std::size_t>(cell)], 0), true));
  EXPECT_EQ(steps, 300);
  EXPECT_GT(fat.BurntFraction(), 0.0);
  // Two clips on the patient's side of the planned cut (0.6), one on the gallbladder's, cut between.
  for (const double s : {0.25, 0.4, 0.85}) CloseJawsOn(*session, InstrumentTool::kClipApplier, kArtery, s);
  ASSERT_EQ(tubes.clips().size(), 3u);
  CloseJawsOn(*session, InstrumentTool::kScissors, kArtery, 0.6);
  ASSERT_EQ(tubes.cuts().size(), 1u);
  EXPECT_FALSE(tubes.Bleeding());
  const calot::CalotMetrics& metrics = *session->calot_metrics();
  EXPECT_TRUE(metrics.AllClipsPlacedCorrectly(StructureKind::kCysticArtery));
  EXPECT_TRUE(metrics.AllDividedBetweenClips(StructureKind::kCysticArtery));
  EXPECT_EQ(metrics.Count(calot::FindingKind::kBleeding), 0);
  EXPECT_EQ(metrics.Count(calot::FindingKind::kClipBeforeCriticalView), 3);  // the view was never reached
  const SessionMetrics m = session->metrics();
  EXPECT_EQ(m.cystic_artery_clips, 3);
  EXPECT_TRUE(m.cystic_artery_clips_correct);
  EXPECT_TRUE(m.cystic_artery_divided_between_clips);
  EXPECT_EQ(m.bleeding_events, 0);
  EXPECT_FALSE(m.calot_passed);  // clipped before the critical view, duct untouched
}

TEST_F(CalotSessionTest, ClippingTheCommonBileDuctEndsTheCase) {
  auto session = NewSession();
  CloseJawsOn(*session, InstrumentTool::kClipApplier, kCommonBileDuct, 0.5);
  EXPECT_TRUE(session->case_ended());
  const SessionMetrics m = session->metrics();
  EXPECT_EQ(m.bile_duct_injuries, 1);
  EXPECT_FALSE(m.calot_passed);
  EXPECT_FALSE(m.success);
  EXPECT_EQ(session->calot_metrics()->Count(calot::FindingKind::kBileDuctInjury), 1);
}

TEST_F(CalotSessionTest, TheRunnerFinishesTheSessionAtTheBileDuctInjury) {
  // The same hands as a recording: open jaws over the common bile duct, then closed, then still.
  auto probe = NewSession();
  const auto& tubes = *probe->calot_tubes();
  const Eigen::Vector3d target = tubes.PositionAt(kCommonBileDuct, 0.5 * tubes.TubeLength_m(kCommonBileDuct));
  device::InputRecording rec;
  const double h = model_->settings.time_step_s;
  for (int i = 0; i < 400; ++i) {
    device::InputFrame f = Frame(InstrumentTool::kClipApplier, RightTipAt(target, i < 2 ? 0.5 : 0.0));
    f.time_s = i * h;
    rec.frames.push_back(f);
  }
  RunnerOptions options;
  options.real_time = false;
  options.calot = CalotSessionSetupFor(*scenario_);
  SessionRunner runner(model_, DefaultCauteryParams(), std::make_shared<device::ReplayInput>(rec), options);
  runner.Start();
  RunnerStatus s;
  for (int i = 0; i < 6000 && !(s = runner.Status()).finished; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_TRUE(s.finished) << s.error;
  EXPECT_TRUE(s.error.empty()) << s.error;
  EXPECT_TRUE(s.case_ended);
  EXPECT_LT(s.session_time_s, 10 * h);  // ended at the clip, not at the recording's end
  ASSERT_TRUE(s.calot_metrics.has_value());
  EXPECT_TRUE(s.calot_metrics->CaseEnded());
  EXPECT_EQ(s.metrics.bile_duct_injuries, 1);
}

TEST_F(CalotSessionTest, TheTubesHoldTheNeckUpAgainstItsSag) {
  // Under the scenario's gravity the gallbladder settles and its neck sags. With the triangle the
  // cystic duct and artery pull the neck back (DissectionScene::SetOutsideLoad): it sags less than
  // on the same model without them, and their pull points against the sag.
  const auto with = NewSession();
  DissectionSession without(model_, DefaultCauteryParams());
  const std::vector<int>& neck_nodes = with->calot_step()->neck_nodes();
  const auto neck_sag = [&](const DissectionSession& s) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    const Eigen::VectorXd& u = s.scene().gallbladder().state().displacement_m;
    for (const int v : neck_nodes) mean += u.segment<3>(3 * v);
    return Eigen::Vector3d(mean / static_cast<double>(neck_nodes.size()));
  };
  const device::InputFrame tools_out{};  // both instruments withdrawn into their ports
  for (int k = 0; k < 400; ++k) {
    with->Step(tools_out);
    without.Step(tools_out);
  }
  const Eigen::Vector3d sag_with = neck_sag(*with), sag_without = neck_sag(without);
  const Eigen::Vector3d pull = with->calot_tubes()->NeckForce_N();
  std::printf("neck sag %.3f mm with the tubes, %.3f mm without; their pull %.4f N (stiffness %.0f N/m)\n",
              1e3 * sag_with.norm(), 1e3 * sag_without.norm(), pull.norm(),
              with->calot_tubes()->NeckStiffness_N_per_m());
  ASSERT_GT(sag_without.norm(), 1e-4);
  EXPECT_LT(sag_with.norm(), 0.9 * sag_without.norm());
  EXPECT_LT(pull.dot(sag_with), 0.0);
  // The tubes' end follows the neck: the pull is the coupling springs' stretch, not a free end.
  EXPECT_GT(pull.norm(), 1e-4);
}

TEST_F(CalotSessionTest, TheHooksWireReachesTheFatAgainstADuctsWall) {
  // The sleeve cell of the cystic duct nearest its centreline (against the wall, on the scope's
  // side): the hook brought onto it with its pedal down pushes the duct only by its 1 mm wire, so
  // its 2 mm burn reaches the cell and takes it within 4 s. (Pushing by the 2.5 mm shaft radius kept
  // every cell nearer the centreline than 2.5 + 1.5 - 2 = 2 mm out of reach: the duct could not
  // be bared with the hook.)
  auto session = NewSession();
  const auto& fat = *session->calot_fat();
  const auto& tubes = *session->calot_tubes();
  const Eigen::Vector3d eye = scenario_->laparoscope.position_m;
  int cell = -1;
  double nearest = 1e9;
  for (std::size_t c = 0; c < fat.cells().size(); ++c) {
    const auto& fc = fat.cells()[c];
    if (fc.anchor_tube != kCysticDuct) continue;
    const Eigen::Vector3d axis_point = tubes.PositionAt(kCysticDuct, fc.anchor_s_m);
    const Eigen::Vector3d p = fat.cell_positions_m()[c];
    if ((p - axis_point).dot(eye - axis_point) <= 0) continue;  // the side the instruments come from
    const double d = (p - axis_point).norm();
    if (d < nearest) nearest = d, cell = static_cast<int>(c);
  }
  ASSERT_GE(cell, 0);
  std::printf("the cell %.2f mm from the duct's centreline (wall at 1.5 mm)\n", 1e3 * nearest);
  ASSERT_LT(nearest, 0.002);
  const auto c = static_cast<std::size_t>(cell);
  // The hook comes in from 6 mm outside the wall, along the line from the axis through the cell,
  // at 1 cm/s with the pedal down, and stays at the cell's place (the duct gives way before it).
  const Eigen::Vector3d axis_point = tubes.PositionAt(kCysticDuct, fat.cells()[c].anchor_s_m);
  const Eigen::Vector3d target = fat.cell_positions_m()[c];
  const Eigen::Vector3d out = (target - axis_point).normalized();
  const double h = model_->settings.time_step_s, approach_m = 0.006;
  for (int i = 0; i < 800 && fat.cells()[c].state == physics::calot::FatCellState::kIntact; ++i) {
    const double left_m = std::max(0.0, approach_m - 0.01 * h * i);
    session->Step(Frame(InstrumentTool::kCauteryHook, RightTipAt(target + left_m * out, 0), true));
  }
  EXPECT_EQ(fat.cells()[c].state, physics::calot::FatCellState::kBurnt);
}

}  // namespace
}  // namespace vesica::app
