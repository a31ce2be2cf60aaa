// The field's static context (issue 30): each organ of the default scenario's [[context_organs]]
// that lies in the scope's view is drawn where an independent pinhole model projects it, in its
// own colour (or that of a context organ in front of it); the same picture without the context
// shows something else there.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "../app/offscreen_render.h"
#include "../app/screen_projection.h"
#include "app/render/laparoscope_view.h"
#include "app/render/scene_meshes.h"
#include "app/scenario/scenario_loader.h"
#include "cie_lab.h"

namespace vesica::app {
namespace {

using testing::OffscreenRender;
using testing::Picture;

constexpr int kWidth = 960, kHeight = 540;

// Mean colour of the 5 x 5 pixels around px.
Eigen::Vector3d MeanAround(const Picture& pic, const Eigen::Vector2d& px) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int dr = -2; dr <= 2; ++dr)
    for (int dc = -2; dc <= 2; ++dc) {
      const auto c = pic.at(static_cast<int>(px.x()) + dc, static_cast<int>(px.y()) + dr);
      sum += Eigen::Vector3d(c.r, c.g, c.b);
    }
  return sum / 25.0;
}

TEST(ContextOrgans, TheDefaultFieldShowsItsContextOrgansWhereTheyProject) {
  Scenario scenario = LoadScenario(DefaultScenarioPath());
  const SceneMeshes meshes = LoadSceneMeshes(scenario);
  ASSERT_GE(scenario.context_organs.size(), 5u) << "the default field names its surroundings";
  Scenario bare = scenario;
  bare.context_organs.clear();
  LaparoscopeView with(scenario, meshes), without(bare, meshes);
  OffscreenRender render(kWidth, kHeight);
  const Picture a = render.Render(with);
  const Picture b = render.Render(without);

  int checked = 0;
  for (const ContextOrgan& organ : scenario.context_organs) {
    // Tubes pass through their points; ellipsoids cover their centre. Only points well inside the
    // picture and in front of everything simulated count (the check is on the organ's own pixels).
    const std::vector<Eigen::Vector3d> points =
        organ.shape == ContextOrgan::Shape::kTube ? organ.points_m : std::vector<Eigen::Vector3d>{organ.centre_m};
    for (const Eigen::Vector3d& p : points) {
      const Eigen::Vector2d px = testing::ProjectToPixel(scenario.laparoscope, p, kWidth, kHeight);
      if (px.x() < 20 || px.y() < 20 || px.x() > kWidth - 20 || px.y() > kHeight - 20) continue;
      const Eigen::Vector3d seen = MeanAround(a, px), bare_seen = MeanAround(b, px);
      const auto lab = [](const Eigen::Vector3d& c) {
        return testing::SrgbToLab(static_cast<int>(c.x()), static_cast<int>(c.y()), static_cast<int>(c.z()));
      };
      const double change = testing::DeltaE76(lab(seen), lab(bare_seen));
      // Hue: the organ's colour ranks its channels; lit, the pixel ranks them the same way.
      const auto order = [](const Eigen::Vector3d& c) { return std::array<bool, 2>{c.x() >= c.y(), c.y() >= c.z()}; };
      std::printf("%-36s at (%4.0f, %4.0f): rgb (%3.0f %3.0f %3.0f), without context (%3.0f %3.0f %3.0f), dE %.1f\n",
                  organ.name.c_str(), px.x(), px.y(), seen.x(), seen.y(), seen.z(), bare_seen.x(), bare_seen.y(),
                  bare_seen.z(), change);
      if (change < 10) continue;  // hidden behind the liver or the gallbladder: nothing to check here
      ++checked;
      // Context organs may lie in front of each other (the fat over the ducts): the pixel has the
      // hue of one of them.
      bool some_organs_hue = false;
      for (const ContextOrgan& other : scenario.context_organs) some_organs_hue |= order(seen) == order(other.rgb);
      EXPECT_TRUE(some_organs_hue) << organ.name;
    }
  }
  EXPECT_GE(checked, 4) << "context organs seen in the picture";
}

}  // namespace
}  // namespace vesica::app
