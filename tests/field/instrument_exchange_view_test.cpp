// The right hand's exchanged instrument is what the picture shows (issue 36): the hook, the clip
// applier (a clip loaded between its open jaws) or the scissors, drawn at the same working point;
// the exchange changes the picture only around the right hand's tip.

#include <gtest/gtest.h>

#include "../app/offscreen_render.h"
#include "../app/screen_projection.h"
#include "app/render/laparoscope_view.h"
#include "app/render/scene_meshes.h"
#include "app/scenario/scenario_loader.h"

namespace vesica::app {
namespace {

using physics::InstrumentTool;
using testing::OffscreenRender;
using testing::Picture;

constexpr int kWidth = 960, kHeight = 540;

struct Changed {
  int near_tip = 0;  // pixels that differ within 60 px of the right tip's projection
  int far = 0;       // pixels that differ farther than 200 px from it
};

Changed Diff(const Picture& a, const Picture& b, const Eigen::Vector2d& tip_px) {
  Changed c;
  for (int row = 0; row < kHeight - 60; ++row)  // above the status strip
    for (int col = 0; col < kWidth; ++col) {
      const auto x = a.at(col, row), y = b.at(col, row);
      if (std::abs(x.r - y.r) + std::abs(x.g - y.g) + std::abs(x.b - y.b) < 30) continue;
      const double d = (Eigen::Vector2d(col, row) - tip_px).norm();
      c.near_tip += d < 60;
      c.far += d > 200;
    }
  return c;
}

TEST(InstrumentExchangeView, TheRightPortsToolIsDrawnAndNothingElseChanges) {
  const Scenario scenario = LoadScenario(DefaultScenarioPath());
  const SceneMeshes meshes = LoadSceneMeshes(scenario);
  LaparoscopeView view(scenario, meshes);
  OffscreenRender render(kWidth, kHeight);
  RenderFrame f;
  f.instruments.resize(2);
  for (std::size_t i = 0; i < 2; ++i) f.instruments[i].pose = view.poses().at(i);
  f.instruments[0].tool = InstrumentTool::kGrasper;
  const InstrumentConfig& right = scenario.instruments[1];
  const Eigen::Vector3d centre = scenario.trocar(right.trocar).position_m;
  const Eigen::Vector3d tip = physics::TipPosition(
      centre, (scenario.laparoscope.look_at_m - centre).normalized(), f.instruments[1].pose);
  const Eigen::Vector2d tip_px = testing::ProjectToPixel(scenario.laparoscope, tip, kWidth, kHeight);
  ASSERT_TRUE(tip_px.x() > 60 && tip_px.x() < kWidth - 60 && tip_px.y() > 60 && tip_px.y() < kHeight - 120)
      << "the right tip is in the picture: " << tip_px.transpose();

  const auto draw = [&](InstrumentTool tool, double jaw_rad) {
    f.instruments[1].tool = tool;
    f.instruments[1].pose.jaw_angle_rad = jaw_rad;
    view.Update(f);
    return render.Render(view);
  };
  const Picture hook = draw(InstrumentTool::kCauteryHook, 0.0);
  const Picture scissors_open = draw(InstrumentTool::kScissors, 0.6);
  const Picture applier_open = draw(InstrumentTool::kClipApplier, 0.6);
  const Picture applier_closed = draw(InstrumentTool::kClipApplier, 0.0);
  const Picture hook_again = draw(InstrumentTool::kCauteryHook, 0.0);

  for (const auto& [name, other] : {std::pair<const char*, const Picture*>{"scissors", &scissors_open},
                                    {"clip applier", &applier_open}}) {
    const Changed c = Diff(hook, *other, tip_px);
    EXPECT_GT(c.near_tip, 100) << name << " is drawn where the hook was";
    EXPECT_EQ(c.far, 0) << name << ": the rest of the picture is unchanged";
  }
  const Changed fired = Diff(applier_open, applier_closed, tip_px);
  EXPECT_GT(fired.near_tip, 30) << "the open jaws and their loaded clip differ from the closed jaws";
  EXPECT_EQ(fired.far, 0);
  const Changed back = Diff(hook, hook_again, tip_px);
  EXPECT_EQ(back.near_tip + back.far, 0) << "exchanging back draws the hook exactly as before";
  // A grasper asked for in the right port is a bad frame: the port keeps its own instrument.
  const Changed bad = Diff(hook, draw(InstrumentTool::kGrasper, 0.0), tip_px);
  EXPECT_EQ(bad.near_tip + bad.far, 0);
}

}  // namespace
}  // namespace vesica::app
