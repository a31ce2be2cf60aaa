// Frame timing: exact stuffed lengths against hand-computed frames and the worst-case bound.
#include "firmware_protocol/codec/frame_timing.h"

#include <gtest/gtest.h>

#include <random>

namespace vesica::fp {
namespace {

TEST(FrameTimingTest, WorstCaseFormulaMatchesPublishedValues) {
  // Davis, Burns, Bril, Lukkien (2007): 8-byte standard frame at most 135 bits incl. 3-bit IFS;
  // 0-byte frame 55 bits; 8-byte extended frame 160 bits.
  EXPECT_EQ(classic_worst_case_bits(8), 135u);
  EXPECT_EQ(classic_worst_case_bits(0), 55u);
  EXPECT_EQ(classic_worst_case_bits(8, true), 160u);
}

TEST(FrameTimingTest, AllZeroFrameHasHandCountedStuffBits) {
  // id 0, DLC 0: SOF + 11 id + RTR + IDE + r0 + 4 DLC = 19 zeros, CRC-15 of zeros is 0: 34 zeros,
  // one stuff bit after every 5 -> 6 stuff bits; + 13 bits of delimiters, ACK, EOF and IFS = 53.
  CanFrame f;
  EXPECT_EQ(classic_exact_bits(f), 53u);
}

TEST(FrameTimingTest, ExactLengthLiesBetweenUnstuffedAndWorstCase) {
  std::mt19937 rng(12345);
  for (int trial = 0; trial < 20000; ++trial) {
    CanFrame f;
    f.id = rng() & 0x7FF;
    f.len = static_cast<std::uint8_t>(rng() % 9);
    for (int i = 0; i < 8; ++i) f.data[i] = static_cast<std::uint8_t>(trial % 3 == 0 ? 0 : rng());
    const std::uint32_t bits = classic_exact_bits(f);
    EXPECT_GE(bits, 47u + 8u * f.len);
    EXPECT_LE(bits, classic_worst_case_bits(f.len));
  }
}

TEST(FrameTimingTest, DurationAtOneMegabitIsOneMicrosecondPerBit) {
  CanFrame f;
  f.id = 0x181;
  f.len = 8;
  BitRates r;
  EXPECT_EQ(frame_duration_ns(f, r), 1000ull * classic_exact_bits(f));
  EXPECT_EQ(frame_duration_ns(f, r, true), 135'000ull);
}

TEST(FrameTimingTest, FdWithBitRateSwitchIsShorterThanClassicForEightBytes) {
  BitRates r;
  CanFrame f;
  f.len = 8;
  f.flags = CanFrame::kFdFrame | CanFrame::kBitRateSwitch;
  const std::uint64_t fd = frame_duration_ns(f, r);
  EXPECT_LT(fd, 135'000ull);
  EXPECT_EQ(fd, fd_worst_case_duration_ns(8, r));
  // 64 bytes at 5 Mbit/s data phase still fit in well under a classic 8-byte frame's double.
  EXPECT_LT(fd_worst_case_duration_ns(64, r), 2 * 135'000ull);
}

}  // namespace
}  // namespace vesica::fp
