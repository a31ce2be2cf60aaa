#include "app/calot/calot_snapshot.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

#include "tests/calot_training/scripted_case.h"

namespace vesica::app::calot {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

CalotSnapshot Valid() {
  CalotSnapshot s;
  s.time_s = 12.4;
  s.structures = testing::VariantStructures(testing::Variant::kStandard);
  s.events.push_back({.kind = CalotEventKind::kClip, .structure = 1, .s = 0.3, .time_s = 12.4});
  return s;
}

TEST(CalotSnapshotTest, AValidSnapshotPasses) { EXPECT_NO_THROW(ValidateSnapshot(Valid(), 12.0)); }

TEST(CalotSnapshotTest, DisplayNameFallsBackToTheKind) {
  StructureState unnamed{.kind = StructureKind::kCommonBileDuct};
  EXPECT_EQ(DisplayName(unnamed), "common bile duct");
  unnamed.name = "CBD";
  EXPECT_EQ(DisplayName(unnamed), "CBD");
}

TEST(CalotSnapshotTest, EachBadFieldIsNamed) {
  const auto fails_with = [](auto change, const std::string& message) {
    CalotSnapshot s = Valid();
    change(s);
    EXPECT_THAT([&] { ValidateSnapshot(s, 12.0); }, ThrowsMessage<CalotInputError>(HasSubstr(message))) << message;
  };
  fails_with([](CalotSnapshot& s) { s.time_s = std::numeric_limits<double>::quiet_NaN(); }, "time_s must be finite");
  fails_with(
      [](CalotSnapshot& s) {
        s.time_s = 11.0;
        s.events.clear();
      },
      "Calot snapshot at t = 11.000 s: time_s is before the previous snapshot's 12 s");
  fails_with([](CalotSnapshot& s) { s.fat_removed_fraction = 1.5; }, "fat_removed_fraction = 1.5 is outside 0..1");
  fails_with([](CalotSnapshot& s) { s.lower_third_separated_fraction = -0.1; },
             "lower_third_separated_fraction = -0.1 is outside 0..1");
  fails_with(
      [](CalotSnapshot& s) {
        s.structures[3].clips_s = {0.2, 1.3};
      },
      "Calot snapshot at t = 12.400 s: structures[3] (common bile duct): clips_s[1] = 1.3 is outside 0..1");
  fails_with([](CalotSnapshot& s) { s.structures[0].cuts_s = {-0.5}; },
             "structures[0] (cystic duct): cuts_s[0] = -0.5 is outside 0..1");
  fails_with([](CalotSnapshot& s) { s.structures[1].planned_cut_s = 1.0; },
             "structures[1] (cystic artery): planned_cut_s = 1 must be strictly between 0 and 1");
  fails_with([](CalotSnapshot& s) { s.structures[2].visible_fraction = 2; }, "visible_fraction = 2 is outside 0..1");
  fails_with([](CalotSnapshot& s) { s.events[0].structure = 4; }, "events[0]: structure 4 is not one of the 4");
  fails_with([](CalotSnapshot& s) { s.events[0].structure = -1; }, "events[0]: structure -1 is not one of the 4");
  fails_with([](CalotSnapshot& s) { s.events[0].s = 1.01; }, "events[0]: s = 1.01 is outside 0..1");
  fails_with([](CalotSnapshot& s) { s.events[0].time_s = 12.5; }, "events[0]: time_s = 12.5 is outside [12, 12.4]");
  fails_with([](CalotSnapshot& s) { s.events[0].time_s = 11.5; }, "events[0]: time_s = 11.5 is outside [12, 12.4]");
  fails_with(
      [](CalotSnapshot& s) {
        s.events[0].time_s = 12.3;
        s.events.push_back({.kind = CalotEventKind::kCut, .structure = 1, .s = 0.5, .time_s = 12.2});
      },
      "events[1]: time_s = 12.2 is outside [12.3, 12.4] (events go in time order");
}

}  // namespace
}  // namespace vesica::app::calot
