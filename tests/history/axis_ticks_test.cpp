#include "app/history/axis_ticks.h"

#include <gtest/gtest.h>

#include <limits>

namespace vesica::app {
namespace {

TEST(AxisTicksTest, NiceStepCoversTheRange) {
  const AxisTicks ticks = NiceTicks(0, 7.3, 6);
  EXPECT_EQ(ticks.step, 2);
  EXPECT_EQ(ticks.values, (std::vector<double>{0, 2, 4, 6, 8}));
  EXPECT_EQ(ticks.decimals, 0);
}

TEST(AxisTicksTest, ExactMultipleIsNotExtended) {
  EXPECT_EQ(NiceTicks(0, 10, 6).values, (std::vector<double>{0, 2, 4, 6, 8, 10}));
  EXPECT_EQ(NiceTicks(0, 900, 6).values, (std::vector<double>{0, 200, 400, 600, 800, 1000}));
}

TEST(AxisTicksTest, SmallValuesGetDecimals) {
  const AxisTicks ticks = NiceTicks(0, 0.87, 6);
  EXPECT_DOUBLE_EQ(ticks.step, 0.2);
  ASSERT_EQ(ticks.values.size(), 6u);
  EXPECT_DOUBLE_EQ(ticks.values.back(), 1.0);
  EXPECT_EQ(ticks.decimals, 1);
  EXPECT_EQ(TickLabel(ticks.values[3], ticks.decimals), "0.6");
}

TEST(AxisTicksTest, NegativeLowEnd) {
  const AxisTicks ticks = NiceTicks(-3, 12, 6);
  EXPECT_EQ(ticks.step, 5);
  EXPECT_EQ(ticks.values, (std::vector<double>{-5, 0, 5, 10, 15}));
}

TEST(AxisTicksTest, NoSpreadAndBadInputCoverUnitRange) {
  const AxisTicks flat = NiceTicks(0, 0, 6);
  EXPECT_DOUBLE_EQ(flat.step, 0.2);
  ASSERT_EQ(flat.values.size(), 6u);
  EXPECT_EQ(flat.values.front(), 0);
  EXPECT_DOUBLE_EQ(flat.values.back(), 1);
  EXPECT_EQ(NiceTicks(std::numeric_limits<double>::quiet_NaN(), 5, 6).values.front(), 0);
  EXPECT_EQ(NiceTicks(std::numeric_limits<double>::quiet_NaN(), 5, 6).values.back(), 1);
  EXPECT_EQ(NiceTicks(0, 10, 0).values, (std::vector<double>{0, 10}));  // max_ticks < 2 counts as 2
}

TEST(AxisTicksTest, SessionNumbers) {
  EXPECT_EQ(SessionNumberTicks(0, 10), std::vector<int>{});
  EXPECT_EQ(SessionNumberTicks(1, 10), std::vector<int>{1});
  EXPECT_EQ(SessionNumberTicks(3, 10), (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(SessionNumberTicks(23, 6), (std::vector<int>{1, 5, 10, 15, 20}));
  EXPECT_EQ(SessionNumberTicks(12, 10), (std::vector<int>{1, 2, 4, 6, 8, 10, 12}));
}

TEST(AxisTicksTest, TickLabelHasNoNegativeZero) {
  EXPECT_EQ(TickLabel(-0.0, 0), "0");
  EXPECT_EQ(TickLabel(-1e-17, 1), "0.0");
  EXPECT_EQ(TickLabel(-2.5, 1), "-2.5");
}

}  // namespace
}  // namespace vesica::app
