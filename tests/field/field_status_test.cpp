// The surgeon's feedback in the field (issue 30): the pedal, the grasp and each arm's link are
// shown in the laparoscope picture itself, without F2. Each state gets its words and its
// colour: the label's pixels are read back from the rendered picture.

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "../app/offscreen_render.h"
#include "app/render/field_status_overlay.h"
#include "app/render/laparoscope_view.h"
#include "app/render/render_colours.h"
#include "app/render/scene_meshes.h"
#include "app/scenario/scenario_loader.h"

namespace vesica::app {
namespace {

using testing::OffscreenRender;
using testing::Picture;
using testing::Rgb;

constexpr int kWidth = 960, kHeight = 540;

class FieldStatusTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scenario_ = new Scenario(LoadScenario(DefaultScenarioPath()));
    meshes_ = new SceneMeshes(LoadSceneMeshes(*scenario_));
  }
  static void TearDownTestSuite() {
    delete meshes_;
    delete scenario_;
  }
  static RenderFrame Frame(bool holding, bool slipping, bool pedal, bool burning) {
    RenderFrame f;
    f.instruments.resize(2);
    for (std::size_t i = 0; i < 2; ++i) f.instruments[i].pose = view_poses_->at(i);
    f.instruments[0].grasping = holding;
    f.instruments[0].slipping = slipping;
    f.instruments[1].pedal_down = pedal;
    f.instruments[1].cautery_active = burning;
    return f;
  }
  // Pixels of the bottom strip (the labels' band) in the given horizontal range that match in
  // `pic` and did not in `before` (the context organs there keep their colours between frames).
  static int Count(const Picture& pic, const Picture& before, int col0, int col1,
                   const std::function<bool(Rgb)>& match, int band_rows = 40) {
    int n = 0;
    for (int row = kHeight - band_rows; row < kHeight; ++row)
      for (int col = col0; col < col1; ++col) n += match(pic.at(col, row)) && !match(before.at(col, row));
    return n;
  }
  static Scenario* scenario_;
  static SceneMeshes* meshes_;
  static const std::vector<physics::InstrumentPose>* view_poses_;
};
Scenario* FieldStatusTest::scenario_ = nullptr;
SceneMeshes* FieldStatusTest::meshes_ = nullptr;
const std::vector<physics::InstrumentPose>* FieldStatusTest::view_poses_ = nullptr;

// Orange-white of the pedal label (kCauteryGlowRgb), green of a holding grasp (kStatusOkRgb),
// amber of a slip (kSlipRgb): the text's anti-aliased core pixels.
bool IsPedalOrange(Rgb c) { return c.r > 200 && c.g > 140 && c.g < 215 && c.b < 120; }
bool IsHoldingGreen(Rgb c) { return c.g > 180 && c.r > 110 && c.r < 160 && c.b > 110 && c.b < 160; }
bool IsSlipAmber(Rgb c) { return c.r > 200 && c.g > 50 && c.g < 120 && c.b < 50; }

TEST_F(FieldStatusTest, PedalAndGraspAreShownInTheFieldInTheirOwnColours) {
  LaparoscopeView view(*scenario_, *meshes_);
  view_poses_ = &view.poses();
  OffscreenRender render(kWidth, kHeight);

  view.Update(Frame(false, false, false, false));
  EXPECT_EQ(view.status().grasp_text(), "grasper: empty");
  EXPECT_EQ(view.status().pedal_text(), "hook: pedal up");
  EXPECT_EQ(view.status().arm_text(), "");
  const Picture idle = render.Render(view);

  view.Update(Frame(true, false, true, false));
  EXPECT_EQ(view.status().grasp_text(), "grasper: holding");
  EXPECT_EQ(view.status().pedal_text(), "CUT  pedal down");
  const Picture active = render.Render(view);

  view.Update(Frame(true, true, true, true));
  EXPECT_EQ(view.status().grasp_text(), "GRASP SLIPPED");
  EXPECT_EQ(view.status().pedal_text(), "CUT  (burning)");
  const Picture slipped = render.Render(view);

  // The grasp label sits at the left (the left hand's), the pedal's at the right.
  const int left = kWidth / 3, right = 2 * kWidth / 3;
  EXPECT_GT(Count(active, idle, right, kWidth, IsPedalOrange), 30);
  EXPECT_EQ(Count(active, idle, 0, right, IsPedalOrange), 0);
  EXPECT_GT(Count(active, idle, 0, left, IsHoldingGreen), 30);
  EXPECT_EQ(Count(active, idle, left, kWidth, IsHoldingGreen), 0);
  EXPECT_EQ(Count(active, idle, 0, left, IsSlipAmber), 0);
  EXPECT_GT(Count(slipped, active, 0, left, IsSlipAmber), 30);
}

TEST_F(FieldStatusTest, TheRightHandsLabelNamesTheExchangedInstrument) {
  LaparoscopeView view(*scenario_, *meshes_);
  view_poses_ = &view.poses();
  RenderFrame f = Frame(false, false, true, false);  // the pedal pressed: only the hook would cut
  f.instruments[1].tool = physics::InstrumentTool::kClipApplier;
  f.instruments[1].pose.jaw_angle_rad = 0.6;
  view.Update(f);
  EXPECT_EQ(view.status().pedal_text(), "clip applier: jaws open");
  f.instruments[1].tool = physics::InstrumentTool::kScissors;
  f.instruments[1].pose.jaw_angle_rad = 0.0;
  view.Update(f);
  EXPECT_EQ(view.status().pedal_text(), "scissors: jaws closed");
  f.instruments[1].tool = physics::InstrumentTool::kCauteryHook;
  view.Update(f);
  EXPECT_EQ(view.status().pedal_text(), "CUT  pedal down");
}

TEST_F(FieldStatusTest, EachArmsLinkIsShownAndAFaultStandsOut) {
  LaparoscopeView view(*scenario_, *meshes_);
  view_poses_ = &view.poses();
  OffscreenRender render(kWidth, kHeight);
  RenderFrame f = Frame(false, false, false, false);
  f.arm_status = {"left arm ok", "right arm ok"};
  view.Update(f);
  EXPECT_EQ(view.status().arm_text(), "left arm ok\nright arm ok");
  const Picture ok = render.Render(view);
  f.arm_status = {"left arm ok", "right arm FAULT overcurrent"};
  view.Update(f);
  EXPECT_EQ(view.status().arm_text(), "left arm ok\nright arm FAULT overcurrent");
  const Picture fault = render.Render(view);
  const int left = kWidth / 3, right = 2 * kWidth / 3;
  EXPECT_GT(Count(fault, ok, left, right, IsSlipAmber, 80), 30);
  // Centred: none in the outer sixths, where the hands' labels are.
  EXPECT_EQ(Count(fault, ok, 0, kWidth / 6, IsSlipAmber, 80) + Count(fault, ok, 5 * kWidth / 6, kWidth, IsSlipAmber, 80),
            0);
}

// An arm's line as long as the picture is wide (an uncalibrated arm says what to run) stands
// above the hands' labels, not over them: none of it in their row.
TEST_F(FieldStatusTest, ALongArmLineStaysAboveTheHandsLabels) {
  LaparoscopeView view(*scenario_, *meshes_);
  view_poses_ = &view.poses();
  OffscreenRender render(kWidth, kHeight);
  RenderFrame f = Frame(false, false, false, false);
  view.Update(f);
  const Picture plain = render.Render(view);
  f.arm_status = {"left arm (node 1): no valid calibration (slot A: blank, slot B: blank); run `vesica-calibrate "
                  "--udp-base-port 24000 calibrate 1` (grasper)",
                  "right arm: ok (hook)"};
  view.Update(f);
  const Picture warned = render.Render(view);
  // The hands' row: 2 % of the height up, one text line (13 px at 540 rows) and its margin.
  const int hands_row = static_cast<int>(0.02 * kHeight) + 20;
  EXPECT_GT(Count(warned, plain, 0, kWidth, IsSlipAmber, 80), 100);  // it is there...
  EXPECT_EQ(Count(warned, plain, 0, kWidth, IsSlipAmber, hands_row), 0);  // ...but not in their row
}

}  // namespace
}  // namespace vesica::app
