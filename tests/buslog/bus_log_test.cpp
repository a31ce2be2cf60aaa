// Bus log writer and reader: every kind of frame round-trips through the text exactly (timestamps
// to the microsecond), and a malformed line stops the reader with its line number.
#include "firmware_protocol/buslog/bus_log_reader.h"
#include "firmware_protocol/buslog/bus_log_writer.h"

#include <gtest/gtest.h>

#include <random>
#include <sstream>

namespace vesica::fp {
namespace {

constexpr std::uint8_t kFdLengths[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 16, 20, 24, 32, 48, 64};

// Frames of every kind candump logs: classic and FD, 11- and 29-bit, remote, with and without BRS.
CanFrame random_frame(std::mt19937& rng) {
  CanFrame f;
  const int kind = static_cast<int>(rng() % 4);
  if (rng() % 2) {
    f.flags |= CanFrame::kExtendedId;
    f.id = rng() & 0x1FFFFFFF;
  } else {
    f.id = rng() & 0x7FF;
  }
  if (kind == 0) {
    f.flags |= CanFrame::kRemote;
    f.len = static_cast<std::uint8_t>(rng() % 9);
    return f;
  }
  if (kind == 1) {
    f.flags |= CanFrame::kFdFrame;
    if (rng() % 2) f.flags |= CanFrame::kBitRateSwitch;
    f.len = kFdLengths[rng() % std::size(kFdLengths)];
  } else {
    f.len = static_cast<std::uint8_t>(rng() % 9);
  }
  for (std::uint8_t i = 0; i < f.len; ++i) f.data[i] = static_cast<std::uint8_t>(rng());
  return f;
}

TEST(BusLogTest, TenThousandFramesOfEveryKindRoundTrip) {
  std::mt19937 rng(32);
  std::vector<BusLogEntry> written;
  std::stringstream text;
  BusLogWriter writer(text);
  long long t_us = 1700000000LL * 1000000;
  for (int i = 0; i < 10000; ++i) {
    t_us += 1 + rng() % 2000;
    written.push_back({Nanoseconds{t_us * 1000}, i % 3 ? "can0" : "vcan12", random_frame(rng)});
    writer.write(written.back());
  }
  EXPECT_EQ(writer.lines_written(), 10000u);
  EXPECT_TRUE(writer.ok());

  std::vector<BusLogEntry> read;
  std::string error;
  ASSERT_TRUE(read_bus_log(text, read, error)) << error;
  ASSERT_EQ(read.size(), written.size());
  for (std::size_t i = 0; i < read.size(); ++i) {
    EXPECT_EQ(read[i].timestamp, written[i].timestamp) << i;
    EXPECT_EQ(read[i].interface, written[i].interface) << i;
    EXPECT_EQ(read[i].frame, written[i].frame) << i;
  }
}

TEST(BusLogTest, SubMicrosecondPartOfATimestampIsTruncated) {
  std::stringstream text;
  BusLogWriter writer(text);
  CanFrame f;
  f.id = 0x080;
  f.len = 1;
  writer.write({Nanoseconds{1'000'001'999}, "can0", f});
  EXPECT_EQ(text.str(), "(0000000001.000001) can0 080#00\n");
  BusLogReader reader(text);
  BusLogEntry e;
  ASSERT_TRUE(reader.next(e));
  EXPECT_EQ(e.timestamp, Nanoseconds{1'000'001'000});
}

TEST(BusLogTest, UnwritableEntryThrowsAndWritesNothing) {
  std::stringstream text;
  BusLogWriter writer(text);
  CanFrame f;
  f.len = 9;
  EXPECT_THROW(writer.write({Nanoseconds{0}, "can0", f}), std::invalid_argument);
  EXPECT_EQ(text.str(), "");
  EXPECT_EQ(writer.lines_written(), 0u);
}

TEST(BusLogTest, ReaderSkipsCommentsAndErrorFramesAndStopsAtAMalformedLineNamingIt) {
  std::istringstream text(
      "# session 2026-11-27, arm 1\n"
      "\n"
      "(1700000000.000001) can0 181#0102\n"
      "(1700000000.000002) can0 20000080#0000000000000000\n"
      "(1700000000.000003) can0 182#03\n"
      "(1700000000.000004) can0 183#0\n"
      "(1700000000.000005) can0 184#05\n");
  BusLogReader reader(text);
  BusLogEntry e;
  ASSERT_TRUE(reader.next(e));
  EXPECT_EQ(e.frame.id, 0x181u);
  EXPECT_EQ(reader.line_number(), 3u);
  ASSERT_TRUE(reader.next(e));
  EXPECT_EQ(e.frame.id, 0x182u);
  EXPECT_EQ(reader.error_frames_skipped(), 1u);
  EXPECT_FALSE(reader.next(e));
  EXPECT_EQ(reader.error(), "line 6, column 26: data '0' is not hex byte pairs");
  EXPECT_FALSE(reader.next(e));  // stays stopped: the frames after a bad line are not trusted
}

TEST(BusLogTest, ReadBusLogKeepsTheFramesBeforeTheBadLine) {
  std::istringstream text("(1700000000.000001) can0 181#01\n(1700000000.000002) can0 999#01\n");
  std::vector<BusLogEntry> read;
  std::string error;
  EXPECT_FALSE(read_bus_log(text, read, error));
  EXPECT_EQ(read.size(), 1u);
  EXPECT_EQ(error, "line 2, column 26: 11-bit CAN id 999 is above 7FF");
}

}  // namespace
}  // namespace vesica::fp
