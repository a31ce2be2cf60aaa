#include "firmware_protocol/emulator/incremental_encoder.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace vesica::fp::emulator {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

TEST(IncrementalEncoderTest, CountsFromPowerUpAngle) {
  IncrementalEncoder enc({1000, 0.5}, 10.0);  // powered up at an arbitrary shaft angle
  enc.Update(10.0 + kTwoPi * 0.2505);
  EXPECT_EQ(enc.count(), 250);
  enc.Update(10.0 - kTwoPi * 0.0105);
  EXPECT_EQ(enc.count(), -11);  // floor toward -inf
}

TEST(IncrementalEncoderTest, IndexLatchesCountAtMountingAngle) {
  // Index at 0.5 rad (+2 pi k); power-up at 0.2 rad, so the first edge is 0.3 rad ahead.
  IncrementalEncoder enc({4096, 0.5}, 0.2);
  enc.Update(0.45);
  EXPECT_FALSE(enc.index_seen());
  enc.Update(0.6);
  ASSERT_TRUE(enc.index_seen());
  const double expected = std::floor(0.3 / (kTwoPi / 4096));
  EXPECT_EQ(enc.index_count(), static_cast<std::int32_t>(expected));
  // Going back across the same edge latches the same count.
  enc.Update(0.1);
  EXPECT_EQ(enc.index_count(), static_cast<std::int32_t>(expected));
  // One revolution later, the next edge sits exactly counts_per_rev further on.
  enc.Update(0.6 + kTwoPi);
  EXPECT_EQ(enc.index_count(), static_cast<std::int32_t>(expected) + 4096);
}

}  // namespace
}  // namespace vesica::fp::emulator
