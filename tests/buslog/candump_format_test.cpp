// candump log lines: the exact text candump writes for each kind of frame, what canplayer also
// accepts, and a stated reason for every malformed line.
#include "firmware_protocol/buslog/candump_format.h"

#include <gtest/gtest.h>

#include <stdexcept>

using namespace std::chrono_literals;

namespace vesica::fp {
namespace {

CanFrame frame(std::uint32_t id, std::initializer_list<std::uint8_t> bytes, std::uint8_t flags = 0) {
  CanFrame f;
  f.id = id;
  f.flags = flags;
  for (std::uint8_t b : bytes) f.data[f.len++] = b;
  return f;
}

TEST(CandumpFormatTest, ClassicFrameIsThreeHexDigitsHashUpperCaseData) {
  EXPECT_EQ(format_candump_frame(frame(0x181, {0xDE, 0xAD, 0xbe, 0xef})), "181#DEADBEEF");
  EXPECT_EQ(format_candump_frame(frame(0x000, {0x01, 0x00})), "000#0100");
  EXPECT_EQ(format_candump_frame(frame(0x7FF, {})), "7FF#");
}

TEST(CandumpFormatTest, ExtendedRemoteAndFdFramesAsCandumpWritesThem) {
  EXPECT_EQ(format_candump_frame(frame(0x1ABCDEF0, {0x11}, CanFrame::kExtendedId)), "1ABCDEF0#11");
  EXPECT_EQ(format_candump_frame(frame(0x00000005, {}, CanFrame::kExtendedId)), "00000005#");
  EXPECT_EQ(format_candump_frame(frame(0x123, {}, CanFrame::kRemote)), "123#R");
  CanFrame rtr3 = frame(0x123, {}, CanFrame::kRemote);
  rtr3.len = 3;
  EXPECT_EQ(format_candump_frame(rtr3), "123#R3");
  EXPECT_EQ(format_candump_frame(frame(0x123, {0xAA, 0xBB}, CanFrame::kFdFrame)), "123##4AABB");
  EXPECT_EQ(format_candump_frame(frame(0x123, {0xAA}, CanFrame::kFdFrame | CanFrame::kBitRateSwitch)), "123##5AA");
  CanFrame fd12 = frame(0x0F0, {}, CanFrame::kFdFrame);
  fd12.len = 12;
  EXPECT_EQ(format_candump_frame(fd12), "0F0##4000000000000000000000000");
}

TEST(CandumpFormatTest, LineHasTenDigitSecondsSixDigitMicrosAndInterface) {
  const BusLogEntry e{Nanoseconds{1700000000123456789}, "vcan0", frame(0x701, {0x05, 0x02, 0x00})};
  EXPECT_EQ(format_candump_line(e), "(1700000000.123456) vcan0 701#050200");
  EXPECT_EQ(format_candump_line({Nanoseconds{1999}, "can0", frame(0x080, {0x07})}), "(0000000000.000001) can0 080#07");
}

TEST(CandumpFormatTest, FramesNoLogLineCanCarryAreRefused) {
  CanFrame long_classic = frame(0x100, {});
  long_classic.len = 9;
  EXPECT_THROW(format_candump_frame(long_classic), std::invalid_argument);
  CanFrame fd9 = frame(0x100, {}, CanFrame::kFdFrame);
  fd9.len = 9;
  EXPECT_THROW(format_candump_frame(fd9), std::invalid_argument);
  EXPECT_THROW(format_candump_frame(frame(0x800, {})), std::invalid_argument);
  EXPECT_THROW(format_candump_frame(frame(0x20000000, {}, CanFrame::kExtendedId)), std::invalid_argument);
  EXPECT_THROW(format_candump_frame(frame(0x100, {}, CanFrame::kFdFrame | CanFrame::kRemote)), std::invalid_argument);
  EXPECT_THROW(format_candump_frame(frame(0x100, {}, CanFrame::kBitRateSwitch)), std::invalid_argument);
  EXPECT_THROW(format_candump_line({Nanoseconds{-1000}, "can0", frame(1, {})}), std::invalid_argument);
  EXPECT_THROW(format_candump_line({0ns, "", frame(1, {})}), std::invalid_argument);
  EXPECT_THROW(format_candump_line({0ns, "can 0", frame(1, {})}), std::invalid_argument);
  EXPECT_THROW(format_candump_line({0ns, "sixteen_chars_xx", frame(1, {})}), std::invalid_argument);
}

TEST(CandumpFormatTest, ParsesWhatCanplayerAccepts) {
  BusLogEntry e;
  std::string err;
  ASSERT_EQ(parse_candump_line("(1700000000.000042) can0 181#de.ad.BE.ef\r", e, err), CandumpLine::Frame) << err;
  EXPECT_EQ(e.timestamp, Nanoseconds{1700000000000042000});
  EXPECT_EQ(e.interface, "can0");
  EXPECT_EQ(e.frame, frame(0x181, {0xDE, 0xAD, 0xBE, 0xEF}));
  // candump right-aligns interface names of different lengths.
  ASSERT_EQ(parse_candump_line("(0000000001.000000)  can0 12345678##3AA", e, err), CandumpLine::Frame) << err;
  EXPECT_EQ(e.frame, frame(0x12345678, {0xAA}, CanFrame::kExtendedId | CanFrame::kFdFrame | CanFrame::kBitRateSwitch));
  // Linux < 6.0 does not set the FD flag (4) in the digit: both forms are FD frames.
  ASSERT_EQ(parse_candump_line("(0000000001.000000) can0 123##0AA", e, err), CandumpLine::Frame) << err;
  EXPECT_EQ(e.frame, frame(0x123, {0xAA}, CanFrame::kFdFrame));
  ASSERT_EQ(parse_candump_line("(0000000001.000000) can0 123##7AA", e, err), CandumpLine::Frame) << err;
  EXPECT_EQ(e.frame, frame(0x123, {0xAA}, CanFrame::kFdFrame | CanFrame::kBitRateSwitch));
  ASSERT_EQ(parse_candump_line("(0000000001.000000) can0 123#r5", e, err), CandumpLine::Frame) << err;
  EXPECT_TRUE(e.frame.remote());
  EXPECT_EQ(e.frame.len, 5);
}

TEST(CandumpFormatTest, CommentsBlankLinesAndErrorFramesAreNotFrames) {
  BusLogEntry e;
  std::string err;
  EXPECT_EQ(parse_candump_line("", e, err), CandumpLine::Ignored);
  EXPECT_EQ(parse_candump_line("# recorded by vesica", e, err), CandumpLine::Ignored);
  EXPECT_EQ(parse_candump_line("(0000000001.000000) can0 20000004#0004000000000000", e, err), CandumpLine::ErrorFrame);
}

TEST(CandumpFormatTest, EachMalformedLineSaysWhereAndWhy) {
  struct Case { const char* line; const char* says; };
  const Case cases[] = {
      {"(1700000000.000042 can0 181#00", "column 1: timestamp has no ')'"},
      {"(1700000000.42) can0 181#00", "column 2: timestamp '1700000000.42' is not seconds.micros (6 digits)"},
      {"(17x0000000.000042) can0 181#00", "column 2: timestamp '17x0000000.000042' is not seconds.micros"},
      {"(99999999999.000000) can0 181#00", "beyond the year 2255"},
      {"(1700000000.000042)can0 181#00", "column 20: no space after the timestamp"},
      {"(1700000000.000042) can0", "column 25: no frame after the interface"},
      {"(1700000000.000042) can0 181#00 extra", "column 32: text after the frame"},
      {"(1700000000.000042) can0 18#00", "column 26: CAN id '18' is not 3 (11-bit) or 8 (29-bit) hex digits"},
      {"(1700000000.000042) can0 G81#00", "column 26: CAN id 'G81' is not hexadecimal"},
      {"(1700000000.000042) can0 800#00", "column 26: 11-bit CAN id 800 is above 7FF"},
      {"(1700000000.000042) can0 C0000001#00", "column 26: 29-bit CAN id C0000001 has flag bits set"},
      {"(1700000000.000042) can0 18100", "column 26: frame '18100' has no '#'"},
      {"(1700000000.000042) can0 181#0", "column 26: data '0' is not hex byte pairs"},
      {"(1700000000.000042) can0 181#000102030405060708", "column 26: data longer than 8 bytes"},
      {"(1700000000.000042) can0 181##", "column 26: CAN FD frame without its flags digit"},
      {"(1700000000.000042) can0 181##8", "column 26: CAN FD flags 8 unknown"},
      {"(1700000000.000042) can0 181##00000000000000000000000", "column 26: CAN FD length 11 is not a DLC step"},
      {"(1700000000.000042) can0 181#R9", "column 26: remote frame length '9' is not 0..8"},
  };
  for (const Case& c : cases) {
    BusLogEntry e;
    std::string err;
    EXPECT_EQ(parse_candump_line(c.line, e, err), CandumpLine::Malformed) << c.line;
    EXPECT_NE(err.find(c.says), std::string::npos) << c.line << " -> " << err;
  }
}

}  // namespace
}  // namespace vesica::fp
