// The committed dissection (data/recordings/dissection.csv) on the default scenario, as the scope
// sees it (issue 30): while the pedal is down the hook's drawn tip is in sight (no liver or
// gallbladder between it and the scope's tip), sampled every 50 ms (the issue asks every 0.5 s);
// and every 0.5 s at least 80 % of the still-attached membrane's area is in sight. Rays are cast
// at the deformed organs' triangles (organ_sight.h), not read from a render. The recording must
// also do the dissection: every spring cut, the gallbladder freed.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "app/render/scene_meshes.h"
#include "app/render/scope_pose.h"
#include "app/replay/session_replay.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_session.h"
#include "app/session/dissection_setup.h"
#include "device/input/input_recording.h"
#include "device/input/replay_input.h"
#include "organ_sight.h"
#include "physics/instrument/instrument_pose.h"

namespace vesica::app {
namespace {

namespace fs = std::filesystem;

TEST(CommittedDissectionSight, TheHookBurnsInSightAndTheMembraneFacesTheScope) {
  const Scenario scenario = LoadScenario(DefaultScenarioPath());
  const auto model = BuildDissectionModelFor(scenario, LoadSceneMeshes(scenario));
  device::ReplayInput input(
      device::ReadInputRecording(fs::path(VESICA_SOURCE_DIR) / "data/recordings/dissection.csv"));
  DissectionSession session(model, DefaultCauteryParams());
  const Eigen::Vector3d eye = ScopePoseOf(scenario.laparoscope).eye_W;
  const physics::InstrumentMount& hook = model->instruments[1];
  const long steps_per_50ms = std::lround(0.05 / model->settings.time_step_s);

  long step = 0, pedal_samples = 0, tip_in_sight = 0, membrane_samples = 0;
  double first_hidden_s = -1, worst_membrane = 1, worst_membrane_at_s = 0;
  RunReplay(session, input, [&](const DissectionSession& s, const SessionStepReport& report) {
    if (++step % steps_per_50ms != 0) return;
    const physics::DissectionScene& scene = s.scene();
    if (report.cautery.pedal_down) {
      ++pedal_samples;
      const InstrumentFrame drawn = s.MakeRenderFrame().instruments[1];
      physics::InstrumentPose pose = drawn.pose;
      pose.insertion_m -= drawn.past_contact_m;  // where InstrumentActors draws the tip
      const Eigen::Vector3d tip = physics::TipPosition(hook.p_RemoteCentre_W, hook.reference_direction_W, pose);
      if (testing::InSight(eye, tip, testing::LiverNow(scene), testing::GallbladderNow(scene), 0.001)) {
        ++tip_in_sight;
      } else {
        if (first_hidden_s < 0) first_hidden_s = s.time_s();
        const Eigen::Vector3d dir = (tip - eye).normalized();
        const double inf = std::numeric_limits<double>::infinity();
        const double nearest =
            std::min(anatomy::FirstRayHit(testing::LiverNow(scene), eye, dir).value_or(inf),
                     anatomy::FirstRayHit(testing::GallbladderNow(scene), eye, dir).value_or(inf));
        std::printf("hook tip hidden at %.2f s: %.1f mm behind an organ surface (touching: %d, drawn %.1f mm short)\n",
                    s.time_s(), 1e3 * ((tip - eye).norm() - nearest),
                    static_cast<int>(report.physics.touches[1].surface), 1e3 * drawn.past_contact_m);
      }
    }
    if (step % (10 * steps_per_50ms) == 0 && scene.tissue().num_alive() > 1) {
      ++membrane_samples;
      const testing::MembraneSight sight = testing::SeeMembrane(scene, eye);
      if (sight.area_m2 > 0 && sight.visible < worst_membrane) {
        worst_membrane = sight.visible;
        worst_membrane_at_s = s.time_s();
      }
    }
  });
  const SessionMetrics metrics = session.metrics();
  std::printf(
      "%.1f s, %d of %d springs cut, gallbladder free: %s; hook tip in sight at %ld of %ld samples with the pedal "
      "down (first hidden at %.2f s); attached membrane in sight: worst %.1f %% at %.1f s over %ld samples\n",
      metrics.duration_s, metrics.springs_cut, metrics.springs_total, metrics.gallbladder_free ? "yes" : "no",
      tip_in_sight, pedal_samples, first_hidden_s, 100 * worst_membrane, worst_membrane_at_s, membrane_samples);
  EXPECT_TRUE(metrics.gallbladder_free) << "the committed recording dissects the gallbladder off its bed";
  ASSERT_GE(pedal_samples, 60) << "the recording burns for at least 3 s";
  EXPECT_EQ(tip_in_sight, pedal_samples) << "the resident never burns blind; first hidden at " << first_hidden_s
                                         << " s";
  ASSERT_GE(membrane_samples, 20);
  EXPECT_GE(worst_membrane, 0.80) << "at " << worst_membrane_at_s << " s";
}

}  // namespace
}  // namespace vesica::app
