#include "device/link_monitor.h"

#include <gtest/gtest.h>

namespace vesica::device {
namespace {

constexpr std::int64_t kMs = 1'000'000;

TEST(LinkMonitorTest, LostAfterTimeoutRestoredAtNextState) {
  LinkMonitor link(10 * kMs);
  EXPECT_FALSE(link.up());
  EXPECT_EQ(link.OnState(0), LinkMonitor::Event::kNone);  // first contact is not a restore
  EXPECT_TRUE(link.up());
  EXPECT_EQ(link.Poll(10 * kMs), LinkMonitor::Event::kNone);  // exactly at the timeout: still up
  EXPECT_EQ(link.Poll(10 * kMs + 1), LinkMonitor::Event::kLost);
  EXPECT_FALSE(link.up());
  EXPECT_EQ(link.Poll(20 * kMs), LinkMonitor::Event::kNone);  // reported once
  EXPECT_EQ(link.OnState(25 * kMs), LinkMonitor::Event::kRestored);
  EXPECT_TRUE(link.up());
  EXPECT_EQ(link.loss_count(), 1u);
  EXPECT_EQ(link.restore_count(), 1u);
}

TEST(LinkMonitorTest, NeverSeenNodeIsNeverLost) {
  LinkMonitor link(kMs);
  EXPECT_EQ(link.Poll(100 * kMs), LinkMonitor::Event::kNone);
  EXPECT_EQ(link.loss_count(), 0u);
  EXPECT_FALSE(link.ever_seen());
}

TEST(LinkMonitorTest, SteadyStatesKeepLinkUp) {
  LinkMonitor link(3 * kMs);
  for (std::int64_t t = 0; t < 1000 * kMs; t += kMs) {
    link.OnState(t);
    EXPECT_EQ(link.Poll(t + kMs / 2), LinkMonitor::Event::kNone);
  }
  EXPECT_EQ(link.loss_count(), 0u);
}

}  // namespace
}  // namespace vesica::device
