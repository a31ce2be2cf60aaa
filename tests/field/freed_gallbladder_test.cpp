// After the last spring (issue 30): the freed gallbladder stays in the grasper's closed jaws. The
// committed dissection is replayed to the moment the gallbladder comes free; the grasper then
// keeps its jaws closed for 2 s more. The grasp must hold, and the points it holds must stay at
// the jaws (within 5 mm of the tool tip) instead of the organ dropping away.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "app/render/scene_meshes.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_session.h"
#include "app/session/dissection_setup.h"
#include "device/input/input_recording.h"

namespace vesica::app {
namespace {

namespace fs = std::filesystem;

TEST(FreedGallbladder, StaysInTheClosedJawsUntilReleased) {
  const Scenario scenario = LoadScenario(DefaultScenarioPath());
  const SceneMeshes meshes = LoadSceneMeshes(scenario);
  const auto model = BuildDissectionModelFor(scenario, meshes);
  const device::InputRecording rec =
      device::ReadInputRecording(fs::path(VESICA_SOURCE_DIR) / "data/recordings/dissection.csv");
  DissectionSession session(model, DefaultCauteryParams());
  const double h = model->settings.time_step_s;
  device::InputFrame last;
  for (const device::InputFrame& frame : rec.frames) {
    if (session.gallbladder_free()) break;
    while (session.time_s() + 1e-12 < frame.time_s && !session.gallbladder_free()) session.Step(last = frame);
  }
  ASSERT_TRUE(session.gallbladder_free()) << "the committed dissection frees the gallbladder";
  const double freed_at_s = session.time_s();
  last.instruments[0].pose.jaw_angle_rad = 0.0;  // the grasper keeps its jaws closed
  last.instruments[1].pedal = false;
  double worst_m = 0;
  bool held = true;
  for (int k = 0; k < static_cast<int>(2.0 / h); ++k) {
    session.Step(last);
    held = held && session.scene().grasp().state() == physics::GraspStateMachine::State::kHolding;
    const physics::Vertices surface = session.scene().gallbladder_surface_positions();
    const auto& triangles = model->gallbladder_boundary.surface.triangles;
    for (const physics::GraspPoint& p : session.scene().grasp().points()) {
      if (p.triangle < 0) continue;
      Eigen::Vector3d q = Eigen::Vector3d::Zero();
      for (int c = 0; c < 3; ++c) q += p.weights[c] * surface.row(triangles(p.triangle, c)).transpose();
      worst_m = std::max(worst_m, (q - session.scene().tool_tip(0)).norm());
    }
  }
  std::printf("freed at %.3f s; held for 2 s: %s; farthest grasped point from the jaws %.2f mm\n", freed_at_s,
              held ? "yes" : "no", 1e3 * worst_m);
  EXPECT_TRUE(held);
  EXPECT_LT(worst_m, 0.005);
}

}  // namespace
}  // namespace vesica::app
