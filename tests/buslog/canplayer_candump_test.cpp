// A log our writer wrote replays with can-utils' canplayer onto vcan0, and candump reads it back
// identically: `candump -l` (its log file) and `candump -L` (log format on stdout) give the same
// frames in the same order, and the same text after the timestamp, line for line.
// Needs a CAN stack: CTest runs it through scripts/uml/run_in_uml.sh (user-mode Linux where this
// kernel has no vcan0); run directly it skips, saying why, unless VESICA_REQUIRE_CAN is set.
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <sstream>

#include "firmware_protocol/buslog/bus_log_reader.h"
#include "firmware_protocol/buslog/bus_log_writer.h"
#include "firmware_protocol/codec/codec.h"
#include "firmware_protocol/transport/socketcan_transport.h"
#include "temp_dir.h"

namespace vesica::fp {
namespace {

constexpr int kFrames = 600;
constexpr std::uint8_t kFdLengths[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 16, 20, 24, 32, 48, 64};

// Our own traffic (protocol messages as the arms and the host send them) and, to cover the format,
// 29-bit, remote and CAN FD frames of every length.
CanFrame random_frame(std::mt19937& rng, int i) {
  CanFrame f;
  switch (i % 5) {
    case 0: {
      const auto node = static_cast<std::uint8_t>(1 + rng() % 2);
      const float a = static_cast<float>(rng() % 6000) * 1e-4f - 0.3f;
      const Message m = i % 2 ? Message{JointState{node, static_cast<std::uint8_t>(i), NodeState::Operational, true,
                                                   Limiter::None, {a, -a, 0.05f}}}
                              : Message{CurrentCommand{node, static_cast<std::uint8_t>(i), CommandMode::JointTorque, {a, a, -a}}};
      EXPECT_EQ(encode(m, f), EncodeError::None);
      return f;
    }
    case 1:
      f.id = rng() & 0x1FFFFFFF;
      f.flags = CanFrame::kExtendedId;
      f.len = static_cast<std::uint8_t>(rng() % 9);
      break;
    case 2:
      f.id = rng() & 0x7FF;
      f.flags = CanFrame::kRemote;
      f.len = static_cast<std::uint8_t>(rng() % 9);
      return f;
    case 3:
      f.id = rng() & 0x7FF;
      f.flags = static_cast<std::uint8_t>(CanFrame::kFdFrame | (rng() % 2 ? CanFrame::kBitRateSwitch : 0));
      f.len = kFdLengths[rng() % std::size(kFdLengths)];
      break;
    default:
      f.id = rng() & 0x7FF;
      f.len = static_cast<std::uint8_t>(rng() % 9);
  }
  for (std::uint8_t b = 0; b < f.len; ++b) f.data[b] = static_cast<std::uint8_t>(rng());
  return f;
}

std::vector<std::string> lines_without_timestamps(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<std::string> out;
  std::string line;
  while (std::getline(in, line))
    if (!line.empty() && line[0] == '(') out.push_back(line.substr(line.find(')') + 1));
  return out;
}

std::vector<BusLogEntry> read_log(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<BusLogEntry> out;
  std::string error;
  EXPECT_TRUE(read_bus_log(in, out, error)) << path << ": " << error;
  return out;
}

TEST(CanplayerCandumpTest, OurLogReplaysOntoVcanAndCandumpReadsBackTheSameFrames) {
  std::string why;
  if (!SocketCanTransport::kernel_supports_can(why)) {
    if (std::getenv("VESICA_REQUIRE_CAN")) FAIL() << "kernel has no AF_CAN: " << why;
    GTEST_SKIP() << "kernel has no AF_CAN (" << why << "); CTest runs this through scripts/uml/run_in_uml.sh";
  }
  test::TempDir dir("vesica-canplayer");
  const auto written_path = dir.path() / "written.log";
  const auto dump_dir = dir.path() / "candump-l";
  const auto dump_L = dir.path() / "candump-L.log";
  std::filesystem::create_directory(dump_dir);

  std::vector<BusLogEntry> written;
  {
    std::ofstream file(written_path);
    BusLogWriter log(file);
    std::mt19937 rng(32);
    long long t_us = 1700000000LL * 1000000;
    for (int i = 0; i < kFrames; ++i) {
      t_us += 1000 + rng() % 2000;  // canplayer keeps these gaps: about 1.2 s in all
      written.push_back({Nanoseconds{t_us * 1000}, "vcan0", random_frame(rng, i)});
      log.write(written.back());
    }
  }

  // Both candumps stop after kFrames frames (or 20 s without one, so a lost frame fails rather
  // than hangs); canplayer starts once both have their receive filters on vcan0
  // (/proc/net/can/rcvlist_all lists one per socket). Their 4 MiB receive buffers (-r; root
  // inside user-mode Linux may exceed rmem_max) hold the whole replay, so a candump that a loaded
  // host schedules late still loses nothing (the default buffer dropped 19 of 600 frames).
  const std::string n = std::to_string(kFrames);
  std::ostringstream script;
  script << "set -e\n"
         << "cd " << dump_dir << "\n"
         << "candump -r 4194304 -l -n " << n << " -T 20000 vcan0 &\n"
         << "candump -r 4194304 -L -n " << n << " -T 20000 vcan0 > " << dump_L << " &\n"
         << "i=0; while [ \"$(grep -c ' vcan0 ' /proc/net/can/rcvlist_all)\" -lt 2 ]; do\n"
         << "  i=$((i+1)); [ $i -lt 1000 ] || { echo 'candump never bound vcan0' >&2; exit 3; }; sleep 0.01; done\n"
         << "canplayer -I " << written_path << "\n"
         << "wait\n";
  const auto script_path = dir.path() / "replay.sh";
  std::ofstream(script_path) << script.str();
  ASSERT_EQ(std::system(("sh " + script_path.string()).c_str()), 0) << script.str();

  std::filesystem::path dump_l;
  for (const auto& e : std::filesystem::directory_iterator(dump_dir)) dump_l = e.path();  // candump-<date>.log
  ASSERT_FALSE(dump_l.empty()) << "candump -l wrote no file";

  for (const auto& path : {dump_l, dump_L}) {
    SCOPED_TRACE(path.string());
    const std::vector<BusLogEntry> got = read_log(path);
    ASSERT_EQ(got.size(), written.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got[i].interface, "vcan0") << i;
      EXPECT_EQ(got[i].frame, written[i].frame) << i;
      if (i > 0) {
        EXPECT_GE(got[i].timestamp, got[i - 1].timestamp) << i;
      }
    }
    // Identically as text too: candump's line after its own timestamp is ours.
    EXPECT_EQ(lines_without_timestamps(path), lines_without_timestamps(written_path));
  }
}

}  // namespace
}  // namespace vesica::fp
