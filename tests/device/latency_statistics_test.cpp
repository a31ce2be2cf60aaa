#include "device/latency_statistics.h"

#include <cmath>

#include <gtest/gtest.h>

namespace vesica::device {
namespace {

TEST(LatencyStatisticsTest, PercentilesOfKnownSequence) {
  LatencyStatistics stats(1000);
  for (int i = 1; i <= 100; ++i) stats.Add(i * 1000);  // 1..100 us, shuffled order irrelevant
  const auto s = stats.Summarize();
  EXPECT_EQ(s.count, 100u);
  EXPECT_EQ(s.min_ns, 1000.0);
  EXPECT_EQ(s.max_ns, 100000.0);
  EXPECT_EQ(s.p50_ns, 50000.0);  // nearest rank: 50th of 100
  EXPECT_EQ(s.p99_ns, 99000.0);
  EXPECT_DOUBLE_EQ(s.mean_ns, 50500.0);
  // Population standard deviation of 1..100 is sqrt((100^2 - 1) / 12).
  EXPECT_NEAR(s.jitter_ns, 1000.0 * std::sqrt((100.0 * 100.0 - 1.0) / 12.0), 1e-6);
}

TEST(LatencyStatisticsTest, RingKeepsOnlyTheNewestWindow) {
  LatencyStatistics stats(4);
  for (int v : {100, 200, 300, 400, 5, 6}) stats.Add(v);
  const auto s = stats.Summarize();
  EXPECT_EQ(s.count, 4u);
  EXPECT_EQ(s.total, 6u);
  EXPECT_EQ(s.min_ns, 5.0);    // 100 and 200 fell out
  EXPECT_EQ(s.max_ns, 400.0);
}

TEST(LatencyStatisticsTest, EmptySummaryIsZero) {
  LatencyStatistics stats;
  const auto s = stats.Summarize();
  EXPECT_EQ(s.count, 0u);
  EXPECT_EQ(s.p99_ns, 0.0);
  stats.Add(7);
  stats.Clear();
  EXPECT_EQ(stats.Summarize().count, 0u);
}

}  // namespace
}  // namespace vesica::device
