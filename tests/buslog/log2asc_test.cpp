// can-utils' log2asc (Vector ASC converter) reads a log our writer wrote: the exact ASC lines for
// a classic, a 29-bit, a remote, a CAN FD and a remote-with-length frame.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "firmware_protocol/buslog/bus_log_writer.h"
#include "temp_dir.h"

namespace vesica::fp {
namespace {

CanFrame frame(std::uint32_t id, std::initializer_list<std::uint8_t> bytes, std::uint8_t flags = 0) {
  CanFrame f;
  f.id = id;
  f.flags = flags;
  for (std::uint8_t b : bytes) f.data[f.len++] = b;
  return f;
}

TEST(Log2AscTest, ConvertsOurLogFrameByFrame) {
  test::TempDir dir("vesica-log2asc");
  const auto log_path = dir.path() / "session.log";
  const auto asc_path = dir.path() / "session.asc";
  {
    std::ofstream file(log_path);
    BusLogWriter log(file);
    const long long t0 = 1700000000000001000;
    log.write({Nanoseconds{t0}, "vcan0", frame(0x181, {0x05, 0x0A, 0xE8, 0x03, 0xD0, 0x07, 0x88, 0x13})});
    log.write({Nanoseconds{t0 + 200000}, "vcan0", frame(0x12345678, {0x01, 0x02}, CanFrame::kExtendedId)});
    log.write({Nanoseconds{t0 + 300000}, "vcan0", frame(0x123, {}, CanFrame::kRemote)});
    log.write({Nanoseconds{t0 + 400000}, "vcan0",
               frame(0x123, {0xAA, 0xBB, 0xCC, 0xDD, 0xEE, 0xFF, 0x00, 0x11, 0x22, 0x33, 0x44, 0x55},
                     CanFrame::kFdFrame | CanFrame::kBitRateSwitch)});
    CanFrame rtr3 = frame(0x123, {}, CanFrame::kRemote);
    rtr3.len = 3;
    log.write({Nanoseconds{t0 + 500000}, "vcan0", rtr3});
  }
  const std::string command = "log2asc -I " + log_path.string() + " -O " + asc_path.string() + " vcan0";
  ASSERT_EQ(std::system(command.c_str()), 0) << command << " (log2asc is in can-utils, scripts/deps.txt)";

  std::ifstream asc(asc_path);
  std::string line;
  std::vector<std::string> frames;
  while (std::getline(asc, line))
    if (line.rfind("   0.", 0) == 0) frames.push_back(line);
  ASSERT_EQ(frames.size(), 5u);
  EXPECT_EQ(frames[0], "   0.000000 1  181             Rx   d 8 05 0A E8 03 D0 07 88 13");
  EXPECT_EQ(frames[1], "   0.000200 1  12345678x       Rx   d 2 01 02");
  EXPECT_EQ(frames[2], "   0.000300 1  123             Rx   r 0");
  EXPECT_EQ(frames[3].substr(0, 90),
            "   0.000400 CANFD   1 Rx        123                                   1 0 9 12 AA BB CC DD");
  EXPECT_EQ(frames[4], "   0.000500 1  123             Rx   r 3");
}

}  // namespace
}  // namespace vesica::fp
