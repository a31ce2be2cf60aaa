#include "fx/cautery_effects.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "fx_test_meshes.h"

namespace vesica::fx {
namespace {

using ::testing::HasSubstr;

// Liver, gallbladder and membrane all use the strip; membrane triangles 0-2 hold spring 0,
// 3-5 hold spring 1.
CauterySurfaces Strips() {
  CauterySurfaces s;
  s.liver = testing::MakeStrip();
  s.gallbladder = testing::MakeStrip();
  s.membrane = testing::MakeStrip();
  s.membrane_element_springs = {{0}, {0}, {0}, {1}, {1}, {1}};
  s.num_springs = 2;
  return s;
}

CauteryParams Params() {
  CauteryParams p;
  p.liver_burn = {.rate_per_s = 0.5, .spread_radius_m = 1.0, .damage_threshold = 0.5};
  p.gallbladder_burn = p.liver_burn;
  p.membrane_burn.spread_radius_m = 1.0;
  p.membrane.fade_rate_per_s = 4.0;
  p.smoke.step_s = 1.0 / 64;
  p.smoke.emission_rate_per_s = 64;
  return p;
}

CauteryContact Touch(CauterySurface surface, int element, bool pedal, double dt = 0.125) {
  CauteryContact c;
  c.surface = surface;
  c.element = element;
  c.p_WTip_W = Eigen::Vector3d(0.5, 0.5, 0.0);
  c.pedal_down = pedal;
  c.dt_s = dt;
  return c;
}

TEST(CauteryEffectsTest, PedalUpBurnsNothingAndMakesNoSmoke) {
  CauteryEffects fx(Strips(), Params());
  for (int k = 0; k < 20; ++k) fx.Step(Touch(CauterySurface::kLiver, 1, false));
  for (int k = 0; k < 20; ++k) fx.Step(Touch(CauterySurface::kMembrane, 1, false));
  EXPECT_EQ(fx.time_s(), 40 * 0.125);
  for (float level : fx.liver_burn().levels()) EXPECT_EQ(level, 0.0f);
  for (float health : fx.membrane().health()) EXPECT_EQ(health, 1.0f);
  EXPECT_TRUE(fx.smoke().particles().empty());
}

TEST(CauteryEffectsTest, PedalDownWithoutContactMakesNoSmoke) {
  CauteryEffects fx(Strips(), Params());
  for (int k = 0; k < 20; ++k) fx.Step(Touch(CauterySurface::kNone, -1, true));
  EXPECT_TRUE(fx.smoke().particles().empty());
}

TEST(CauteryEffectsTest, BurnsOnlyTheTouchedSurfaceAndSmokesAtTheTip) {
  CauteryEffects fx(Strips(), Params());
  for (int k = 0; k < 4; ++k) fx.Step(Touch(CauterySurface::kGallbladder, 1, true));
  EXPECT_EQ(fx.gallbladder_burn().level(1), 0.25);
  EXPECT_EQ(fx.liver_burn().level(1), 0.0);
  EXPECT_EQ(fx.smoke().particles().size(), 32u);  // 0.5 s at 64 per second
  EXPECT_EQ(fx.smoke().particles().back().p_W, Eigen::Vector3d(0.5, 0.5, 0.0));
}

TEST(CauteryEffectsTest, DamageSumsLiverAndGallbladderButNotMembrane) {
  CauteryEffects fx(Strips(), Params());
  for (int k = 0; k < 5; ++k) fx.Step(Touch(CauterySurface::kLiver, 4, true));  // level 0.3125
  EXPECT_EQ(fx.damaged_area_m2(), 0.0);
  for (int k = 0; k < 3; ++k) fx.Step(Touch(CauterySurface::kLiver, 4, true));  // 0.5: at, not past
  EXPECT_EQ(fx.damaged_area_m2(), 0.0);
  fx.Step(Touch(CauterySurface::kLiver, 4, true));
  EXPECT_DOUBLE_EQ(fx.damaged_area_m2(), 0.5);
  ASSERT_EQ(fx.liver_burn().damage_events().size(), 1u);
  EXPECT_EQ(fx.liver_burn().damage_events()[0].time_s, 9 * 0.125);
  for (int k = 0; k < 9; ++k) fx.Step(Touch(CauterySurface::kGallbladder, 0, true));
  EXPECT_DOUBLE_EQ(fx.damaged_area_m2(), 1.0);
  for (int k = 0; k < 40; ++k) fx.Step(Touch(CauterySurface::kMembrane, 2, true));
  EXPECT_DOUBLE_EQ(fx.damaged_area_m2(), 1.0);
}

TEST(CauteryEffectsTest, BurningEveryMembraneElementFreesTheGallbladder) {
  CauteryEffects fx(Strips(), Params());
  // 0.25 s at 4 per second removes an element: two steps of 0.125 s each.
  for (int e = 0; e < 6; ++e) {
    fx.Step(Touch(CauterySurface::kMembrane, e, true));
    EXPECT_FALSE(fx.membrane().element_removed(e));
    fx.Step(Touch(CauterySurface::kMembrane, e, true));
    EXPECT_TRUE(fx.membrane().element_removed(e));
    EXPECT_EQ(fx.membrane().spring_cut(0), e >= 2);
    EXPECT_EQ(fx.membrane().spring_cut(1), e >= 5);
  }
  EXPECT_TRUE(fx.membrane().gallbladder_free());
  ASSERT_EQ(fx.membrane().spring_cuts().size(), 2u);
  EXPECT_EQ(fx.membrane().spring_cuts()[0].time_s, 6 * 0.125);
  EXPECT_EQ(fx.membrane().spring_cuts()[1].time_s, 12 * 0.125);
  EXPECT_GT(fx.membrane_burn().level(0), 0.0);  // membrane blackens while it fades
}

TEST(CauteryEffectsTest, SeveralMembraneElementsUnderTheHookFadeTogether) {
  CauteryEffects fx(Strips(), Params());
  CauteryContact c = Touch(CauterySurface::kMembrane, 0, true);
  c.more_membrane_elements = {1, 2};
  fx.Step(c);
  fx.Step(c);  // 0.25 s: all three removed, spring 0 (elements 0-2) cut, spring 1 untouched
  for (int e = 0; e < 3; ++e) EXPECT_TRUE(fx.membrane().element_removed(e)) << e;
  for (int e = 3; e < 6; ++e) EXPECT_FALSE(fx.membrane().element_removed(e)) << e;
  EXPECT_TRUE(fx.membrane().spring_cut(0));
  EXPECT_FALSE(fx.membrane().spring_cut(1));
  EXPECT_GT(fx.membrane_burn().level(1), 0.0);
  EXPECT_GT(fx.membrane_burn().level(2), 0.0);

  CauteryContact bad = Touch(CauterySurface::kMembrane, 3, true);
  bad.more_membrane_elements = {4, 6};
  EXPECT_THAT([&] { fx.Step(bad); }, ::testing::ThrowsMessage<std::invalid_argument>(
                                         HasSubstr("membrane surface: more_membrane_elements 6 out of range")));
  CauteryContact on_liver = Touch(CauterySurface::kLiver, 3, true);
  on_liver.more_membrane_elements = {4};
  EXPECT_THAT([&] { fx.Step(on_liver); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("more_membrane_elements given")));
  EXPECT_FALSE(fx.membrane().element_removed(4));  // rejected contacts change nothing
}

TEST(CauteryEffectsTest, ReplayIsBitIdentical) {
  auto run = [] {
    CauteryEffects fx(Strips(), Params());
    for (int k = 0; k < 200; ++k) {
      const auto surface = static_cast<CauterySurface>(k % 4);
      CauteryContact c = Touch(surface, k % 6, (k / 7) % 2 == 0, 0.004 + 0.001 * (k % 5));
      c.p_WTip_W = Eigen::Vector3d(0.01 * k, 0.5, std::sin(0.3 * k));
      if (surface == CauterySurface::kNone) c.element = -1;
      fx.Step(c);
    }
    return fx;
  };
  const CauteryEffects a = run();
  const CauteryEffects b = run();
  EXPECT_EQ(a.liver_burn().levels(), b.liver_burn().levels());
  EXPECT_EQ(a.gallbladder_burn().levels(), b.gallbladder_burn().levels());
  EXPECT_EQ(a.membrane().health(), b.membrane().health());
  ASSERT_EQ(a.smoke().particles().size(), b.smoke().particles().size());
  ASSERT_FALSE(a.smoke().particles().empty());
  for (size_t i = 0; i < a.smoke().particles().size(); ++i) {
    EXPECT_EQ(a.smoke().particles()[i].p_W, b.smoke().particles()[i].p_W);
    EXPECT_EQ(a.smoke().particles()[i].alpha, b.smoke().particles()[i].alpha);
  }
}

TEST(CauteryEffectsTest, RejectsBadContactAndKeepsState) {
  CauteryEffects fx(Strips(), Params());
  fx.Step(Touch(CauterySurface::kLiver, 1, true));
  const double t = fx.time_s();
  const std::vector<float> levels = fx.liver_burn().levels();

  EXPECT_THAT(
      [&] { fx.Step(Touch(CauterySurface::kLiver, 6, true)); },
      ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("liver surface: element 6 out of range [0, 6)")));
  EXPECT_THAT([&] { fx.Step(Touch(CauterySurface::kMembrane, -1, true)); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("membrane surface: element -1 out of range")));
  EXPECT_THAT([&] { fx.Step(Touch(CauterySurface::kLiver, 1, true, -0.01)); },
              ::testing::ThrowsMessage<std::invalid_argument>(
                  HasSubstr("CauteryContact: dt_s must be finite and >= 0, got -0.01")));
  CauteryContact nan_tip = Touch(CauterySurface::kLiver, 1, true);
  nan_tip.p_WTip_W.x() = std::nan("");
  EXPECT_THAT([&] { fx.Step(nan_tip); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("CauteryContact: p_WTip_W is not finite")));
  CauteryContact bad_weights = Touch(CauterySurface::kLiver, 1, true);
  bad_weights.barycentric = Eigen::Vector3d(0.5, 0.5, 0.5);
  EXPECT_THAT([&] { fx.Step(bad_weights); }, ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("barycentric")));

  EXPECT_EQ(fx.time_s(), t);
  EXPECT_EQ(fx.liver_burn().levels(), levels);

  CauterySurfaces mismatched = Strips();
  mismatched.membrane_element_springs.pop_back();
  EXPECT_THAT([&] { CauteryEffects bad(mismatched, Params()); },
              ::testing::ThrowsMessage<std::invalid_argument>(
                  HasSubstr("membrane_element_springs has 5 entries, membrane has 6 triangles")));
}

}  // namespace
}  // namespace vesica::fx
