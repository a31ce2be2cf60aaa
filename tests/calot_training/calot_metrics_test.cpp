#include "app/calot/calot_metrics.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "app/calot/case_outcome.h"
#include "tests/calot_training/scripted_case.h"

namespace vesica::app::calot {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using testing::kCommonBileDuct;
using testing::kCommonHepaticDuct;
using testing::kCysticArtery;
using testing::kCysticDuct;
using testing::ScriptedCase;
using testing::Variant;

CalotMetrics Observed(const ScriptedCase& script) {
  CalotMetrics metrics;
  for (const CalotSnapshot& snapshot : script.snapshots()) metrics.Observe(snapshot);
  return metrics;
}

std::vector<ReasonKind> Kinds(const CaseOutcome& outcome) {
  std::vector<ReasonKind> kinds;
  for (const CaseReason& reason : outcome.reasons) kinds.push_back(reason.kind);
  return kinds;
}

std::string VariantTestName(const ::testing::TestParamInfo<Variant>& variant) {
  return testing::VariantName(variant.param);
}

class CorrectDissectionTest : public ::testing::TestWithParam<Variant> {};

TEST_P(CorrectDissectionTest, ReachesTheCriticalViewFirstAndPasses) {
  const ScriptedCase script = testing::CorrectDissection(GetParam());
  const CalotMetrics m = Observed(script);
  // Six 10 s steps of dissection, then the step that completes the view at 60.5 s.
  ASSERT_TRUE(m.CriticalViewTime().has_value());
  EXPECT_DOUBLE_EQ(*m.CriticalViewTime(), 60.5);
  EXPECT_DOUBLE_EQ(*m.FirstClipTime(), 62.5);
  EXPECT_TRUE(m.CriticalViewBeforeFirstClip());
  EXPECT_EQ(m.ClipsOn(StructureKind::kCysticDuct), 3);
  EXPECT_EQ(m.ClipsOn(StructureKind::kCysticArtery), 3);
  for (int i : {kCysticDuct, kCysticArtery}) {
    const StructureHistory& st = m.Structures()[i];
    EXPECT_EQ(st.ClipsOnPatientSide(), 2) << st.name;
    EXPECT_EQ(st.ClipsOnGallbladderSide(), 1) << st.name;
    EXPECT_TRUE(st.ClipsPlacedCorrectly()) << st.name;
    EXPECT_TRUE(st.DividedBetweenClips()) << st.name;
    ASSERT_EQ(st.cuts.size(), 1u);
    EXPECT_DOUBLE_EQ(st.cuts[0].s, script.planned_cut_s(i));
  }
  EXPECT_TRUE(m.AllDividedBetweenClips(StructureKind::kCysticDuct));
  EXPECT_TRUE(m.AllDividedBetweenClips(StructureKind::kCysticArtery));
  EXPECT_TRUE(m.Findings().empty());
  EXPECT_FALSE(m.CaseEnded());
  const CaseOutcome outcome = JudgeCase(m);
  EXPECT_TRUE(outcome.passed);
  EXPECT_FALSE(outcome.critical_error);
  EXPECT_TRUE(outcome.reasons.empty());
  EXPECT_EQ(OutcomeHeadline(outcome), "Passed");
}

INSTANTIATE_TEST_SUITE_P(EachVariant, CorrectDissectionTest, ::testing::ValuesIn(testing::kAllVariants),
                         VariantTestName);

class ClipBeforeCriticalViewTest : public ::testing::TestWithParam<Variant> {};

TEST_P(ClipBeforeCriticalViewTest, IsFlaggedWithItsTime) {
  ScriptedCase script(GetParam());
  script.SetDissection(0.5, 0.2);  // half the fat still there
  script.ExposeCysticStructures();
  script.Advance(12.4);
  script.Clip(kCysticArtery, 0.3);
  script.Advance(1.0);  // the clip at 13.4 s
  script.ReachCriticalView();
  script.Clip(kCysticArtery, 0.4);
  script.Clip(kCysticArtery, 0.8);
  script.Cut(kCysticArtery, script.planned_cut_s(kCysticArtery));
  script.Advance(1.0);
  script.ClipAndDivideCorrectly(kCysticDuct);
  const CalotMetrics m = Observed(script);
  EXPECT_DOUBLE_EQ(*m.FirstClipTime(), 13.4);
  EXPECT_DOUBLE_EQ(*m.CriticalViewTime(), 13.9);
  EXPECT_FALSE(m.CriticalViewBeforeFirstClip());
  ASSERT_EQ(m.Findings().size(), 1u);
  EXPECT_EQ(m.Findings()[0].kind, FindingKind::kClipBeforeCriticalView);
  EXPECT_EQ(m.Findings()[0].structure, kCysticArtery);
  const CaseOutcome outcome = JudgeCase(m);
  EXPECT_FALSE(outcome.passed);
  EXPECT_FALSE(outcome.critical_error);
  EXPECT_THAT(Kinds(outcome), ElementsAre(ReasonKind::kActedBeforeCriticalView));
  EXPECT_THAT(outcome.reasons[0].text, HasSubstr("at 13.4 s before the critical view of safety"));
  EXPECT_EQ(OutcomeHeadline(outcome), "Failed");
}

INSTANTIATE_TEST_SUITE_P(EachVariant, ClipBeforeCriticalViewTest, ::testing::ValuesIn(testing::kAllVariants),
                         VariantTestName);

TEST(CalotMetricsTest, AClipInTheStepThatCompletesTheViewCameBeforeIt) {
  ScriptedCase script;
  script.SetDissection(0.95, 1.0);
  script.ExposeCysticStructures();
  script.Clip(kCysticDuct, 0.3);
  script.Advance(5.0);
  const CalotMetrics m = Observed(script);
  EXPECT_DOUBLE_EQ(*m.CriticalViewTime(), 5.0);
  EXPECT_DOUBLE_EQ(*m.FirstClipTime(), 5.0);
  EXPECT_FALSE(m.CriticalViewBeforeFirstClip());  // the same time, but the clip came first
  ASSERT_EQ(m.Findings().size(), 1u);
  EXPECT_EQ(m.Findings()[0].kind, FindingKind::kClipBeforeCriticalView);
  EXPECT_TRUE(m.Findings()[0].before_critical_view);
}

class UnclippedArteryCutTest : public ::testing::TestWithParam<Variant> {};

TEST_P(UnclippedArteryCutTest, CountsABleed) {
  ScriptedCase script(GetParam());
  script.ReachCriticalView();
  script.Cut(kCysticArtery, script.planned_cut_s(kCysticArtery));
  script.SetBleeding(kCysticArtery, true);  // the model says so in the same step: one bleed, not two
  script.Advance(2.0);
  script.Advance(2.0);  // still bleeding: the same bleed
  const CalotMetrics m = Observed(script);
  EXPECT_EQ(m.Count(FindingKind::kBleeding), 1);
  EXPECT_EQ(m.Count(FindingKind::kBileLeak), 0);
  const Finding& bleed = m.Findings()[0];
  EXPECT_EQ(bleed.structure, kCysticArtery);
  EXPECT_DOUBLE_EQ(bleed.time_s, 2.5);
  EXPECT_FALSE(bleed.before_critical_view);
  const CaseOutcome outcome = JudgeCase(m);
  EXPECT_FALSE(outcome.passed);
  EXPECT_THAT(Kinds(outcome), ::testing::Contains(ReasonKind::kBleeding));
  EXPECT_THAT(outcome.reasons[0].text, HasSubstr("cut at 2.5 s with no clip on the patient's side: bleeding"));
}

INSTANTIATE_TEST_SUITE_P(EachVariant, UnclippedArteryCutTest, ::testing::ValuesIn(testing::kAllVariants),
                         VariantTestName);

TEST(CalotMetricsTest, AnArteryCutOnThePatientSideOfItsClipsBleedsAndOneBeyondThemDoesNot) {
  ScriptedCase script;
  script.ReachCriticalView();
  script.Clip(kCysticArtery, 0.4);
  script.Clip(kCysticArtery, 0.5);
  script.Cut(kCysticArtery, 0.3);  // below both clips: the hepatic side is open
  script.Advance(1.0);
  script.Cut(kCysticArtery, 0.6);  // above them: patient's side clipped, the gallbladder's side open
  script.Advance(1.0);
  const CalotMetrics m = Observed(script);
  EXPECT_EQ(m.Count(FindingKind::kBleeding), 1);
  const StructureHistory& artery = m.Structures()[kCysticArtery];
  ASSERT_EQ(artery.cuts.size(), 2u);
  EXPECT_FALSE(artery.cuts[0].patient_side_clipped);
  EXPECT_TRUE(artery.cuts[0].gallbladder_side_clipped);
  EXPECT_TRUE(artery.cuts[1].patient_side_clipped);
  EXPECT_FALSE(artery.cuts[1].gallbladder_side_clipped);
  EXPECT_FALSE(artery.DividedBetweenClips());
}

TEST(CalotMetricsTest, ACysticDuctCutWithAnOpenEndLeaksBile) {
  ScriptedCase script;
  script.ReachCriticalView();
  script.Clip(kCysticDuct, 0.3);
  script.Clip(kCysticDuct, 0.4);
  script.Cut(kCysticDuct, 0.6);  // no clip on the gallbladder's side: bile runs out of the gallbladder
  script.Advance(1.0);
  const CalotMetrics m = Observed(script);
  EXPECT_EQ(m.Count(FindingKind::kBileLeak), 1);
  EXPECT_EQ(m.Count(FindingKind::kBleeding), 0);
  const CaseOutcome outcome = JudgeCase(m);
  EXPECT_THAT(Kinds(outcome),
              ::testing::IsSupersetOf({ReasonKind::kBileLeak, ReasonKind::kClipsMisplaced,
                                       ReasonKind::kNotDividedBetweenClips, ReasonKind::kNotDivided}));  // the artery
}

TEST(CalotMetricsTest, ABleedTheModelReportsWithoutACutIsCountedOnceUntilItStops) {
  ScriptedCase script;
  script.ReachCriticalView();
  script.SetBleeding(kCysticArtery, true);  // e.g. torn by traction
  script.Advance(1.0);
  script.Advance(1.0);
  script.SetBleeding(kCysticArtery, false);
  script.Advance(1.0);
  script.SetBleeding(kCysticArtery, true);  // a second one
  script.Advance(1.0);
  const CalotMetrics m = Observed(script);
  ASSERT_EQ(m.Count(FindingKind::kBleeding), 2);
  EXPECT_FALSE(m.Findings()[0].s.has_value());
  EXPECT_DOUBLE_EQ(m.Findings()[0].time_s, 1.5);
  EXPECT_DOUBLE_EQ(m.Findings()[1].time_s, 4.5);
  EXPECT_THAT(JudgeCase(m).reasons[0].text, "Bleeding from the cystic artery at 1.5 s");
}

class BileDuctClipTest : public ::testing::TestWithParam<Variant> {};

TEST_P(BileDuctClipTest, IsTheCriticalErrorAndEndsTheCase) {
  ScriptedCase script(GetParam());
  script.SetDissection(0.4, 0.1);
  script.Advance(12.0);
  script.Clip(kCommonBileDuct, 0.7);
  script.Advance(0.4);  // at 12.4 s, before the critical view
  script.ReachCriticalView();
  script.ClipAndDivideCorrectly(kCysticDuct);  // ignored: the case has ended
  const CalotMetrics m = Observed(script);
  EXPECT_TRUE(m.CaseEnded());
  EXPECT_DOUBLE_EQ(m.time_s(), 12.4);
  EXPECT_EQ(m.Count(FindingKind::kBileDuctInjury), 1);
  EXPECT_EQ(m.ClipsOn(StructureKind::kCommonBileDuct), 1);
  EXPECT_EQ(m.ClipsOn(StructureKind::kCysticDuct), 0);
  EXPECT_FALSE(m.CriticalViewTime().has_value());
  const CaseOutcome outcome = JudgeCase(m);
  EXPECT_FALSE(outcome.passed);
  EXPECT_TRUE(outcome.critical_error);
  ASSERT_FALSE(outcome.reasons.empty());
  EXPECT_EQ(outcome.reasons[0].kind, ReasonKind::kBileDuctInjury);
  EXPECT_EQ(outcome.reasons[0].text,
            "Clip placed on the common bile duct at 12.4 s before the critical view of safety: bile duct injury, the "
            "case ends");
  EXPECT_EQ(OutcomeHeadline(outcome), "Failed: bile duct injury");
}

INSTANTIATE_TEST_SUITE_P(EachVariant, BileDuctClipTest, ::testing::ValuesIn(testing::kAllVariants), VariantTestName);

TEST(CalotMetricsTest, ACutThroughTheCommonHepaticDuctAfterTheViewIsAnInjuryToo) {
  ScriptedCase script;
  script.ReachCriticalView();
  script.Cut(kCommonHepaticDuct, 0.5);
  script.Clip(kCysticDuct, 0.2);  // later in the same step: ignored
  script.Advance(1.0);
  const CalotMetrics m = Observed(script);
  EXPECT_TRUE(m.CaseEnded());
  EXPECT_EQ(m.ClipsOn(StructureKind::kCysticDuct), 0);
  const CaseOutcome outcome = JudgeCase(m);
  EXPECT_THAT(Kinds(outcome), ElementsAre(ReasonKind::kBileDuctInjury));
  EXPECT_EQ(outcome.reasons[0].text,
            "Cut made through the common hepatic duct at 1.5 s: bile duct injury, the case ends");
}

TEST(CalotMetricsTest, ClipsAllOnOneSideOfTheCutPointAreMisplaced) {
  ScriptedCase script;
  script.ReachCriticalView();
  const double cut = script.planned_cut_s(kCysticDuct);
  for (double s : {cut - 0.3, cut - 0.2, cut - 0.1}) script.Clip(kCysticDuct, s);
  script.Advance(1.0);
  const CalotMetrics m = Observed(script);
  const StructureHistory& duct = m.Structures()[kCysticDuct];
  EXPECT_EQ(duct.ClipsOnPatientSide(), 3);
  EXPECT_EQ(duct.ClipsOnGallbladderSide(), 0);
  EXPECT_FALSE(duct.ClipsPlacedCorrectly());
  const CaseOutcome outcome = JudgeCase(m);
  ASSERT_GE(outcome.reasons.size(), 1u);
  EXPECT_EQ(outcome.reasons[0].text,
            "Cystic duct: 3 clips on the patient's side of the cut point (2 needed), 0 on the gallbladder's side (1 "
            "needed)");
}

TEST(CalotMetricsTest, NothingDoneAndNoViewSaysWhichCriteriaAreMissing) {
  ScriptedCase script;
  script.SetDissection(0.5, 0.95);
  script.SetVisible(kCysticDuct, 0.9);
  script.Advance(30.0);
  const CaseOutcome outcome = JudgeCase(Observed(script));
  ASSERT_FALSE(outcome.reasons.empty());
  EXPECT_EQ(outcome.reasons[0].text,
            "The critical view of safety was not reached (fat left in the triangle; 1 structure seen entering the "
            "gallbladder, 2 needed)");
}

TEST(CalotMetricsTest, StructuresThatChangeBetweenSnapshotsAreRefused) {
  ScriptedCase script;
  script.Advance(1.0);
  CalotMetrics m;
  m.Observe(script.snapshots()[0]);
  CalotSnapshot changed = script.snapshots()[0];
  changed.time_s = 2.0;
  changed.structures.pop_back();
  EXPECT_THAT([&] { m.Observe(changed); },
              ::testing::ThrowsMessage<CalotInputError>(HasSubstr("the number of structures differs")));
  changed = script.snapshots()[0];
  changed.time_s = 2.0;
  changed.structures[1].kind = StructureKind::kCysticDuct;
  EXPECT_THAT([&] { m.Observe(changed); },
              ::testing::ThrowsMessage<CalotInputError>(HasSubstr("structures[1]'s kind differs")));
  EXPECT_THAT([] { CalotMetrics bad({.fat_removed_min = -1}); },
              ::testing::ThrowsMessage<CalotInputError>(HasSubstr("fat_removed_min")));
}

}  // namespace
}  // namespace vesica::app::calot
