// Burning in the surgeon's view (issue 30: "aimed at the membrane, the hook disappears under the
// gallbladder, so the resident burns blind"). In cholecystectomy.toml the grasper
// takes the gallbladder and pulls it laterally, then the hook burns the connective tissue in the
// slot beside it, target after target, with the pedal down. Every 50 ms while the pedal is down
// the hook's tip must be in the scope's sight (no liver or gallbladder between), springs must be
// cut, and the membrane still attached must stay in sight.
//
// VESICA_SURGEON_VIEW_RECORDING=<file> writes the driven input as a recording (docs/anatomy.md:
// the picture of the burn is made from it with vesica-replay).

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>

#include "app/anatomy/surgeon_view_layout.h"
#include "app/render/scene_meshes.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_session.h"
#include "app/session/dissection_setup.h"
#include "device/input/input_recording.h"
#include "organ_sight.h"
#include "physics/instrument/instrument_pose.h"
#include "scope_rays.h"

namespace vesica::app {
namespace {

namespace fs = std::filesystem;
using anatomy::FirstRayHit;

TEST(SurgeonViewBurn, TheHookBurnsTheMembraneInSightOfTheScope) {
  const Scenario scenario =
      LoadScenario(fs::path(VESICA_SOURCE_DIR) / "data/scenarios/cholecystectomy.toml");
  const SceneMeshes meshes = LoadSceneMeshes(scenario);
  const auto model = BuildDissectionModelFor(scenario, meshes);
  DissectionSession session(model, DefaultCauteryParams());
  const physics::DissectionScene& scene = session.scene();
  const physics::InstrumentMount& grasper = model->instruments[0];
  const physics::InstrumentMount& hook = model->instruments[1];
  const Eigen::Vector3d eye = testing::ScopeEye(scenario.laparoscope);
  const double h = model->settings.time_step_s;

  device::InputRecording recording;
  recording.scenario_name = scenario.name;
  device::InputFrame frame;
  frame.instruments[0].pose =
      physics::AimAt(grasper.p_RemoteCentre_W, scenario.laparoscope.look_at_m, 0.05, grasper.reference_direction_W);
  frame.instruments[0].pose.jaw_angle_rad = 0.5;
  frame.instruments[1].pose =
      physics::AimAt(hook.p_RemoteCentre_W, scenario.laparoscope.look_at_m, 0.05, hook.reference_direction_W);
  int cut = 0, pedal_samples = 0, tip_in_sight = 0;
  double worst_hidden_m = 0;
  auto step = [&](double seconds) {
    for (int k = 0; k < static_cast<int>(seconds / h + 0.5); ++k) {
      frame.time_s = session.time_s();
      recording.frames.push_back(frame);
      cut += session.Step(frame).springs_cut;
      if (frame.instruments[1].pedal && scene.steps() % 10 == 0) {
        ++pedal_samples;
        const physics::TriangleMesh liver = testing::LiverNow(scene), gallbladder = testing::GallbladderNow(scene);
        const Eigen::Vector3d tip = scene.tool_tip(1);
        if (testing::InSight(eye, tip, liver, gallbladder, 0.001)) {
          ++tip_in_sight;
        } else {
          const Eigen::Vector3d dir = (tip - eye).normalized();
          const double inf = std::numeric_limits<double>::infinity();
          worst_hidden_m =
              std::max(worst_hidden_m, (tip - eye).norm() - std::min(FirstRayHit(liver, eye, dir).value_or(inf),
                                                                     FirstRayHit(gallbladder, eye, dir).value_or(inf)));
        }
      }
    }
  };
  auto aim = [](const physics::InstrumentMount& m, const Eigen::Vector3d& target, double insertion) {
    return physics::AimAt(m.p_RemoteCentre_W, target, insertion, m.reference_direction_W);
  };

  step(1.0);  // the organs settle under the assistant's hold and gravity
  // The grasper takes the gallbladder where its line to Hartmann's pouch meets it, and pulls
  // laterally (to the patient's right) 2.5 cm over 1 s.
  const Eigen::Vector3d pouch = anatomy::SurgeonViewGallbladder(anatomy::SurgeonViewLiver().frame).points_m[3];
  const Eigen::Vector3d to_pouch = (pouch - grasper.p_RemoteCentre_W).normalized();
  const auto surface = FirstRayHit(testing::GallbladderNow(scene), grasper.p_RemoteCentre_W, to_pouch);
  ASSERT_TRUE(surface.has_value());
  const Eigen::Vector3d grip = grasper.p_RemoteCentre_W + *surface * to_pouch;
  frame.instruments[0].pose = aim(grasper, grip, *surface - 0.01);
  frame.instruments[0].pose.jaw_angle_rad = 0.5;
  step(0.2);
  frame.instruments[0].pose = aim(grasper, grip, *surface + 0.001);
  frame.instruments[0].pose.jaw_angle_rad = 0.5;
  step(0.3);
  frame.instruments[0].pose.jaw_angle_rad = 0.0;
  step(0.2);
  ASSERT_EQ(scene.grasp().state(), physics::GraspStateMachine::State::kHolding);
  const Eigen::Vector3d pull(-0.025, 0.005, 0.0);
  for (int k = 1; k <= 20; ++k) {
    const Eigen::Vector3d target = grip + (k / 20.0) * pull;
    frame.instruments[0].pose = aim(grasper, target, (target - grasper.p_RemoteCentre_W).norm());
    step(0.05);
  }

  // The hook: to the nearest still-attached membrane triangle it can reach clear of the organs,
  // 5 mm short of it, then with the pedal down 2 mm past it; eight targets.
  for (int target_no = 0; target_no < 8 && scene.tissue().num_alive() > 0; ++target_no) {
    const physics::Vertices points = scene.membrane_points();
    const physics::TissueMembrane& membrane = scene.tissue().membrane;
    const physics::TriangleMesh liver = testing::LiverNow(scene), gallbladder = testing::GallbladderNow(scene);
    double best = std::numeric_limits<double>::infinity();
    Eigen::Vector3d target = Eigen::Vector3d::Zero();
    for (Eigen::Index f = 0; f < membrane.triangles.rows(); ++f) {
      if (!scene.tissue().springs[static_cast<size_t>(membrane.springs(f, 0))].alive ||
          !scene.tissue().springs[static_cast<size_t>(membrane.springs(f, 1))].alive)
        continue;
      const Eigen::Vector3d c = (points.row(membrane.triangles(f, 0)) + points.row(membrane.triangles(f, 1)) +
                                 points.row(membrane.triangles(f, 2)))
                                    .transpose() /
                                3.0;
      if (!testing::InSight(hook.p_RemoteCentre_W, c, liver, gallbladder, 0.0005)) continue;
      const double d = (c - scene.tool_tip(1)).norm();
      if (d < best) {
        best = d;
        target = c;
      }
    }
    if (std::isinf(best)) break;  // nothing left that the hook reaches
    const double reach = (target - hook.p_RemoteCentre_W).norm();
    frame.instruments[1].pedal = false;
    frame.instruments[1].pose = aim(hook, target, reach - 0.005);
    step(0.3);
    frame.instruments[1].pedal = true;
    for (int k = 1; k <= 10; ++k) {
      frame.instruments[1].pose = aim(hook, target, reach - 0.005 + 0.007 * k / 10.0);
      step(0.05);
    }
  }
  frame.instruments[1].pedal = false;
  frame.instruments[1].pose = aim(hook, scenario.laparoscope.look_at_m, 0.05);
  step(0.3);

  const testing::MembraneSight sight = testing::SeeMembrane(scene, eye);
  std::printf(
      "%d of %zu springs cut; hook tip in sight at %d of %d samples with the pedal down (worst hidden %.1f mm); "
      "the still-attached membrane %.1f %% in sight\n",
      cut, scene.tissue().springs.size(), tip_in_sight, pedal_samples, 1e3 * worst_hidden_m, 100 * sight.visible);
  if (const char* out = std::getenv("VESICA_SURGEON_VIEW_RECORDING")) device::WriteInputRecording(out, recording);
  EXPECT_GE(cut, 5) << "the hook burns the connective tissue";
  EXPECT_GE(pedal_samples, 40);
  EXPECT_EQ(tip_in_sight, pedal_samples) << "the resident never burns blind";
  if (scene.tissue().num_alive() > 0) {
    EXPECT_GE(sight.visible, 0.8);
  }
}

}  // namespace
}  // namespace vesica::app
