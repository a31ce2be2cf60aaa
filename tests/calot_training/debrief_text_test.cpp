#include "app/calot/debrief_text.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/calot_training/scripted_case.h"

namespace vesica::app::calot {
namespace {

using ::testing::Contains;
using ::testing::ElementsAre;
using testing::kCommonBileDuct;
using ::testing::Pair;
using testing::ScriptedCase;

CalotMetrics Observed(const ScriptedCase& script) {
  CalotMetrics metrics;
  for (const CalotSnapshot& snapshot : script.snapshots()) metrics.Observe(snapshot);
  return metrics;
}

TEST(DebriefTextTest, APassedCaseListsItsMetricsAndNoReasons) {
  const DebriefText text = MakeDebriefText(Observed(testing::CorrectDissection(testing::Variant::kStandard)));
  EXPECT_EQ(text.title, "Calot's triangle: debrief");
  EXPECT_EQ(text.headline, "Passed");
  EXPECT_TRUE(text.reasons.empty());
  // 60.5 s the view; the artery's clips at 62.5, 64.5, 66.5 s, its cut at 68.5 s; then the duct's.
  EXPECT_THAT(
      text.metrics,
      ElementsAre(Pair("Time", "76.5 s"), Pair("Critical view of safety", "reached at 60.5 s, before the first clip"),
                  Pair("Clips, cystic duct", "3: 2 on the patient's side, 1 on the gallbladder's side"),
                  Pair("Division, cystic duct", "between clips at 76.5 s"),
                  Pair("Clips, cystic artery", "3: 2 on the patient's side, 1 on the gallbladder's side"),
                  Pair("Division, cystic artery", "between clips at 68.5 s"), Pair("Bleeding events", "0"),
                  Pair("Bile leaks", "0"), Pair("Bile duct injuries", "0")));
}

TEST(DebriefTextTest, TheCriticalErrorSaysWhatWhereAndWhen) {
  ScriptedCase script;
  script.SetDissection(0.4, 0.1);
  script.Advance(12.0);
  script.Clip(kCommonBileDuct, 0.7);
  script.Advance(0.4);
  const DebriefText text = MakeDebriefText(Observed(script));
  EXPECT_EQ(text.headline, "Failed: bile duct injury");
  ASSERT_FALSE(text.reasons.empty());
  EXPECT_EQ(text.reasons[0],
            "Clip placed on the common bile duct at 12.4 s before the critical view of safety: bile duct injury, the "
            "case ends");
  EXPECT_THAT(text.metrics, Contains(Pair("Critical view of safety", "not reached")));
  EXPECT_THAT(text.metrics, Contains(Pair("Clips, common bile duct", "1 (bile duct injury)")));
  EXPECT_THAT(text.metrics, Contains(Pair("Bile duct injuries", "1")));
  EXPECT_THAT(text.metrics, Contains(Pair("Division, cystic duct", "not divided")));
}

}  // namespace
}  // namespace vesica::app::calot
