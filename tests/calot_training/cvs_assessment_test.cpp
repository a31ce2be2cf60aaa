#include "app/calot/cvs_assessment.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/calot_training/scripted_case.h"

namespace vesica::app::calot {
namespace {

using testing::kCommonBileDuct;
using testing::kCysticArtery;
using testing::kCysticDuct;

// All three criteria met with a margin: fat 95 % removed, lower third fully separated, the
// cystic duct and artery in view entering the gallbladder, the common ducts out of view.
CalotSnapshot CriticalView() {
  CalotSnapshot s;
  s.time_s = 60;
  s.structures = testing::VariantStructures(testing::Variant::kStandard);
  s.fat_removed_fraction = 0.95;
  s.lower_third_separated_fraction = 1.0;
  s.structures[kCysticDuct].visible_fraction = 0.8;
  s.structures[kCysticArtery].visible_fraction = 0.7;
  return s;
}

TEST(CvsAssessmentTest, AllThreeCriteriaGiveTheCriticalView) {
  const CvsAssessment a = AssessCriticalView(CriticalView());
  EXPECT_TRUE(a.triangle_cleared);
  EXPECT_TRUE(a.lower_third_separated);
  EXPECT_EQ(a.structures_seen_entering, 2);
  EXPECT_TRUE(a.two_structures_seen);
  EXPECT_TRUE(a.Achieved());
}

TEST(CvsAssessmentTest, FatLeftInTheTriangleAloneFails) {
  CalotSnapshot s = CriticalView();
  s.fat_removed_fraction = 0.85;
  const CvsAssessment a = AssessCriticalView(s);
  EXPECT_FALSE(a.triangle_cleared);
  EXPECT_TRUE(a.lower_third_separated);
  EXPECT_TRUE(a.two_structures_seen);
  EXPECT_FALSE(a.Achieved());
}

TEST(CvsAssessmentTest, LowerThirdStillOnTheBedAloneFails) {
  CalotSnapshot s = CriticalView();
  s.lower_third_separated_fraction = 0.6;
  const CvsAssessment a = AssessCriticalView(s);
  EXPECT_TRUE(a.triangle_cleared);
  EXPECT_FALSE(a.lower_third_separated);
  EXPECT_TRUE(a.two_structures_seen);
  EXPECT_FALSE(a.Achieved());
}

TEST(CvsAssessmentTest, OnlyOneStructureSeenAloneFails) {
  CalotSnapshot s = CriticalView();
  s.structures[kCysticArtery].visible_fraction = 0.3;  // still under fat behind the duct
  const CvsAssessment a = AssessCriticalView(s);
  EXPECT_TRUE(a.triangle_cleared);
  EXPECT_TRUE(a.lower_third_separated);
  EXPECT_EQ(a.structures_seen_entering, 1);
  EXPECT_FALSE(a.two_structures_seen);
  EXPECT_FALSE(a.Achieved());
}

TEST(CvsAssessmentTest, AThirdStructureSeenEnteringAloneFails) {
  // A common bile duct that seems to run into the gallbladder (a low insertion misread, or a
  // duct tented up by traction) is three structures: not the critical view.
  CalotSnapshot s = CriticalView();
  s.structures[kCommonBileDuct].enters_gallbladder = true;
  s.structures[kCommonBileDuct].visible_fraction = 0.9;
  const CvsAssessment a = AssessCriticalView(s);
  EXPECT_EQ(a.structures_seen_entering, 3);
  EXPECT_FALSE(a.two_structures_seen);
  EXPECT_FALSE(a.Achieved());
}

TEST(CvsAssessmentTest, AVisibleStructureThatDoesNotEnterTheGallbladderDoesNotCount) {
  CalotSnapshot s = CriticalView();
  s.structures[kCommonBileDuct].visible_fraction = 1.0;  // in view, but it runs past the gallbladder
  EXPECT_EQ(AssessCriticalView(s).structures_seen_entering, 2);
  EXPECT_TRUE(AssessCriticalView(s).Achieved());
}

TEST(CvsAssessmentTest, ThresholdsAreInclusiveAndConfigurable) {
  CalotSnapshot s = CriticalView();
  s.fat_removed_fraction = 0.9;
  s.lower_third_separated_fraction = 0.9;
  s.structures[kCysticDuct].visible_fraction = 0.5;
  EXPECT_TRUE(AssessCriticalView(s).Achieved());  // each exactly at its default threshold
  CvsThresholds strict;
  strict.fat_removed_min = 0.99;
  EXPECT_FALSE(AssessCriticalView(s, strict).triangle_cleared);
  strict = {};
  strict.lower_third_separated_min = 1.0;
  EXPECT_FALSE(AssessCriticalView(s, strict).lower_third_separated);
  strict = {};
  strict.visible_fraction_min = 0.6;
  EXPECT_EQ(AssessCriticalView(s, strict).structures_seen_entering, 1);
}

TEST(CvsAssessmentTest, BadThresholdsAreNamed) {
  CvsThresholds t;
  t.lower_third_separated_min = 1.5;
  EXPECT_THAT([&] { ValidateThresholds(t); },
              ::testing::ThrowsMessage<CalotInputError>(::testing::HasSubstr("lower_third_separated_min = 1.5")));
  EXPECT_NO_THROW(ValidateThresholds({}));
}

}  // namespace
}  // namespace vesica::app::calot
