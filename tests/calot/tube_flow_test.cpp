// Flow of bile and blood through clipped and cut tubes (docs/calot.md): what the metrics read as
// a bleed, a bile leak, or a clean division between clips.
#include "physics/calot/tube_flow.h"

#include <gtest/gtest.h>

#include "physics/calot/triangle_structures.h"

namespace vesica::physics::calot {
namespace {

constexpr int kDuct = 0, kArtery = 1, kBile = 3;

TEST(TubeFlowTest, AClippedTubeCarriesNoFlowPastTheClip) {
  TubeFlowState artery{0.04, true, false, {}, {}};
  EXPECT_TRUE(FlowPasses(artery, 0.03));
  EXPECT_TRUE(FluidAt(artery, 0.03));
  artery.clips_s_m = {0.02};
  EXPECT_TRUE(FluidAt(artery, 0.01));   // upstream: blood held back by the clip
  EXPECT_FALSE(FluidAt(artery, 0.03));  // downstream: none
  EXPECT_FALSE(FlowPasses(artery, 0.01));
  EXPECT_FALSE(FlowPasses(artery, 0.03));
  // A duct pressurised from both sides: bile on both sides of the clip, flowing through neither.
  TubeFlowState duct{0.05, true, true, {0.025}, {}};
  EXPECT_TRUE(FluidAt(duct, 0.01));
  EXPECT_TRUE(FluidAt(duct, 0.04));
  EXPECT_FALSE(FlowPasses(duct, 0.04));
}

TEST(TubeFlowTest, LeaksFollowClipsAndCuts) {
  // Unclipped artery cut: the patient's side bleeds; the gallbladder's side does not (not pressurised).
  const std::vector<OpenEndLeak> bleed = LeakingEnds({0.04, true, false, {}, {0.02}});
  ASSERT_EQ(bleed.size(), 1u);
  EXPECT_TRUE(bleed[0].patient_side);
  EXPECT_DOUBLE_EQ(bleed[0].s_m, 0.02);
  // Divided between clips: dry.
  EXPECT_TRUE(LeakingEnds({0.04, true, false, {0.010, 0.014, 0.030}, {0.022}}).empty());
  EXPECT_TRUE(LeakingEnds({0.05, true, true, {0.010, 0.014, 0.030}, {0.022}}).empty());
  // The duct clipped on the patient's side only: the gallbladder's bile runs out.
  const std::vector<OpenEndLeak> bile = LeakingEnds({0.05, true, true, {0.010, 0.014}, {0.022}});
  ASSERT_EQ(bile.size(), 1u);
  EXPECT_FALSE(bile[0].patient_side);
  // The piece between two cuts is dry, its outer ends leak.
  const std::vector<OpenEndLeak> twice = LeakingEnds({0.05, true, true, {}, {0.02, 0.03}});
  ASSERT_EQ(twice.size(), 2u);
  EXPECT_TRUE(twice[0].patient_side);
  EXPECT_DOUBLE_EQ(twice[0].s_m, 0.02);
  EXPECT_FALSE(twice[1].patient_side);
  EXPECT_DOUBLE_EQ(twice[1].s_m, 0.03);
}

TEST(TubeFlowTest, TheStructuresReportBleedsAndBileLeaksWhereTheyAre) {
  TriangleStructures s(DefaultTriangleDescription());
  EXPECT_TRUE(s.Leaks().empty());
  ASSERT_EQ(s.Cut(kArtery, 0.02), ToolActionResult::kDone);  // unclipped
  EXPECT_TRUE(s.Bleeding());
  EXPECT_FALSE(s.BileLeaking());
  const std::vector<TubeLeak> leaks = s.Leaks();
  ASSERT_EQ(leaks.size(), 1u);
  EXPECT_EQ(leaks[0].fluid, Fluid::kBlood);
  EXPECT_TRUE(leaks[0].patient_side);
  EXPECT_LT((leaks[0].p_W_m - s.PositionAt(kArtery, 0.02)).norm(), 1e-9);

  // The duct correctly: two clips on the patient's side, one on the gallbladder's, cut between.
  TriangleStructures clean(DefaultTriangleDescription());
  const double l = clean.TubeLength_m(kDuct);
  for (double at : {0.45 * l, 0.5 * l, 0.7 * l}) ASSERT_EQ(clean.PlaceClip(kDuct, at), ToolActionResult::kDone);
  ASSERT_EQ(clean.Cut(kDuct, 0.6 * l), ToolActionResult::kDone);
  EXPECT_TRUE(clean.Leaks().empty());
  EXPECT_FALSE(clean.FlowPasses(kDuct, 0.2 * l));
  EXPECT_TRUE(clean.FluidAt(kDuct, 0.2 * l));
  EXPECT_FALSE(clean.FluidAt(kDuct, 0.6 * l));  // between the clips: dry
  EXPECT_TRUE(clean.FlowPasses(kBile, 0.02));   // the common bile duct still drains

  // Without the gallbladder's clip, the gallbladder's bile leaks.
  TriangleStructures leaky(DefaultTriangleDescription());
  for (double at : {0.45 * l, 0.5 * l}) ASSERT_EQ(leaky.PlaceClip(kDuct, at), ToolActionResult::kDone);
  ASSERT_EQ(leaky.Cut(kDuct, 0.6 * l), ToolActionResult::kDone);
  EXPECT_TRUE(leaky.BileLeaking());
  ASSERT_EQ(leaky.Leaks().size(), 1u);
  EXPECT_FALSE(leaky.Leaks()[0].patient_side);
}

}  // namespace
}  // namespace vesica::physics::calot
