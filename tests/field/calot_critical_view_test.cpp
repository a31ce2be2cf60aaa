// The critical view of safety as the resident sees it (issue 36's image point "after a correct
// dissection both structures are visible separately"). The scripted correct dissection
// (app/replay/calot_scripted_surgeon.h, real instrument input only) runs on each variant; at the
// step the session first judges the critical view reached, the laparoscope's picture is drawn at
// 1280 x 720 and compared with an independent projection of the model's tubes
// (tests/calot_scripted/calot_seen_samples.h: the test's pinhole, rays past the liver, the
// gallbladder, every intact fat cell and the drawn instruments): the cystic duct and the cystic artery each have
// samples in sight apart from the other's (their projected discs do not overlap), and there the picture shows each in
// its own colour (grey-green duct, red artery), not fat. Not the short cystic duct: there the session judges the view
// reached while the 8 mm duct is seen apart from the artery, which crosses in front of it at the neck, over 1.5 mm only
// (3 of 16 samples; the scripted sessions' test finds a fifth of it apart only after the division). That is a finding
// about the critical view's third criterion (docs/calot-training.md), not hidden by a lower bar here.
// VESICA_CALOT_CRITICAL_VIEW_PNG_DIR=dir saves each variant's picture, to look at.

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#include "../app/offscreen_render.h"
#include "app/render/laparoscope_view.h"
#include "app/render/scene_meshes.h"
#include "app/replay/calot_scripted_surgeon.h"
#include "app/scenario/scenario_loader.h"
#include "app/session/dissection_session.h"
#include "app/session/dissection_setup.h"
#include "calot_colours.h"
#include "tests/calot_scripted/calot_seen_samples.h"

namespace vesica::app {
namespace {

namespace fs = std::filesystem;
using testing::Picture;
using testing::ProjectedSample;

constexpr int kWidth = 1280, kHeight = 720;
constexpr int kCysticDuct = 0, kCysticArtery = 1;
// Apart and in sight over at least a fifth of each one's length (as the scripted sessions' test
// asks at the session's end), and drawn in its own colour at 80 % of those samples (the rest: shading at the
// silhouette).
constexpr double kMinimumApartShare = 0.2;
constexpr double kMinimumOwnColour = 0.8;

struct AtTheCriticalView {
  Picture picture;
  std::vector<ProjectedSample> duct_apart, artery_apart;
  double time_s = 0;
};

class CalotCriticalView : public ::testing::TestWithParam<const char*> {};

TEST_P(CalotCriticalView, ShowsTheCysticDuctAndArteryEachApartInItsOwnColour) {
  const Scenario s = LoadScenario(fs::path(VESICA_SOURCE_DIR) / "data/scenarios" / GetParam());
  const SceneMeshes meshes = LoadSceneMeshes(s);
  const auto model = BuildDissectionModelFor(s, meshes);
  const CalotSessionSetup setup = *CalotSessionSetupFor(s, double(kWidth) / kHeight);
  DissectionSession session(model, DefaultCauteryParams(), setup);
  LaparoscopeView view(s, meshes);
  testing::OffscreenRender render(kWidth, kHeight);

  std::optional<AtTheCriticalView> seen;
  CalotSurgeonSettings settings;
  settings.scope_eye_W = setup.camera.p_Eye_W_m;
  settings.on_step = [&](const DissectionSession& now, const SessionStepReport&) {
    if (seen || !now.calot_metrics()->CriticalViewTime()) return;
    view.Update(now.MakeRenderFrame());
    AtTheCriticalView at{render.Render(view), {}, {}, now.time_s()};
    const auto duct = testing::SeenSamples(s, *model, now, kCysticDuct, kWidth, kHeight);
    const auto artery = testing::SeenSamples(s, *model, now, kCysticArtery, kWidth, kHeight);
    at.duct_apart = testing::SamplesApart(duct, artery);
    at.artery_apart = testing::SamplesApart(artery, duct);
    seen = std::move(at);
    if (const char* dir = std::getenv("VESICA_CALOT_CRITICAL_VIEW_PNG_DIR"))
      render.SaveLast(fs::path(dir) / (fs::path(GetParam()).stem().string() + "-critical-view.png"));
  };
  RunScriptedCalot(session, CalotScript::kCorrectDissection, settings);
  ASSERT_TRUE(seen.has_value()) << "the correct dissection never reached the critical view";

  const auto own_colour = [&](const std::vector<ProjectedSample>& samples, bool artery) {
    int own = 0;
    for (const ProjectedSample& x : samples) {
      const testing::Rgb c = seen->picture.at(static_cast<int>(x.pixel.x()), static_cast<int>(x.pixel.y()));
      own += artery ? Artery(c) : Duct(c);
    }
    return samples.empty() ? 0.0 : double(own) / static_cast<double>(samples.size());
  };
  const double duct_own = own_colour(seen->duct_apart, false), artery_own = own_colour(seen->artery_apart, true);
  std::printf(
      "%s: critical view at %.2f s; duct %zu samples apart, %.0f %% grey-green; artery %zu apart, %.0f %% red\n",
      GetParam(), seen->time_s, seen->duct_apart.size(), 100 * duct_own, seen->artery_apart.size(), 100 * artery_own);
  const auto& tubes = *session.calot_tubes();
  const auto samples_of = [&](int tube) { return static_cast<int>(tubes.TubeLength_m(tube) / 0.0005) + 1; };
  EXPECT_GE(static_cast<double>(seen->duct_apart.size()), kMinimumApartShare * samples_of(kCysticDuct));
  EXPECT_GE(static_cast<double>(seen->artery_apart.size()), kMinimumApartShare * samples_of(kCysticArtery));
  EXPECT_GE(duct_own, kMinimumOwnColour);
  EXPECT_GE(artery_own, kMinimumOwnColour);
}

INSTANTIATE_TEST_SUITE_P(Variants, CalotCriticalView,
                         ::testing::Values("calot-standard.toml", "calot-low-insertion.toml",
                                           "calot-anterior-artery.toml"),
                         testing::CalotVariantName);

}  // namespace
}  // namespace vesica::app
