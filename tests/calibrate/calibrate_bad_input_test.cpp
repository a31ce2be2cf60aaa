// Bad input to the real vesica-calibrate: each gives a clear message and its documented exit
// code, and writes nothing (no report, no image, the arm's flash as it was).
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "app/calibrate/exit_codes.h"
#include "firmware_protocol/codec/codec.h"
#include "firmware_protocol/node/calibration_slot.h"
#include "firmware_protocol/transport/udp_transport.h"
#include "tool_process.h"

namespace vesica::app::calibrate {
namespace {

using testing::FilesUnder;
using testing::ReadBytes;
using testing::RunTool;
using namespace std::chrono_literals;

std::uint16_t FreeBasePort() {
  for (int tries = 0; tries < 50; ++tries) {
    std::string error;
    auto probe = fp::UdpTransport::open({.local_port = 0}, error);
    const int base = probe ? probe->local_port() : 0;
    probe.reset();
    if (base == 0 || base > 60000) continue;
    bool free = true;
    for (int p = base; p <= base + 3 && free; ++p)
      free = fp::UdpTransport::open({.local_port = static_cast<std::uint16_t>(p)}, error) != nullptr;
    if (free) return static_cast<std::uint16_t>(base);
  }
  return 0;
}

// A stored calibration of emulated arm 1 (seed 5) in dir: the starting point of several tests.
void CalibrateOnce(const std::string& dir) {
  const auto run =
      RunTool({"--emulated", "5", "--dir", dir, "--yes", "--quiet", "--date", "1790000000", "calibrate", "1"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
}

TEST(CalibrateBadInput, AnUnknownArmIsRefusedBeforeAnythingOpens) {
  const std::string dir = testing::FreshDir("unknown-arm");
  for (const char* arm : {"3", "middle", "0"}) {
    const auto run = RunTool({"--emulated", "5", "--dir", dir, "info", arm});
    EXPECT_EQ(run.exit_code, kExitNoArm) << arm;
    EXPECT_NE(run.err.find(std::string("unknown arm '") + arm + "': the arms are 1 (left) and 2 (right)"),
              std::string::npos)
        << run.err;
  }
  const auto json = RunTool({"--dir", dir, "--json", "calibrate", "7"});
  EXPECT_EQ(json.exit_code, kExitNoArm);
  EXPECT_EQ(json.json()["error"]["name"], "no_arm");
  EXPECT_FALSE(std::filesystem::exists(dir)) << "something was written";
}

TEST(CalibrateBadInput, ABadCommandLineIsAUsageErrorAndWritesNothing) {
  const std::string dir = testing::FreshDir("usage");
  auto run = RunTool({"--dir", dir, "--json", "--bogus", "scan"});
  EXPECT_EQ(run.exit_code, kExitUsage);
  EXPECT_EQ(run.json()["error"]["message"], "The following argument was not expected: --bogus");
  run = RunTool({"--dir", dir, "--json", "calibrate", "1", "--joint", "elbow"});
  EXPECT_EQ(run.exit_code, kExitUsage);
  EXPECT_EQ(run.json()["error"]["message"], "unknown joint 'elbow': yaw, pitch or insertion");
  run = RunTool({"--dir", dir, "calibrate", "1", "--step", "spin"});
  EXPECT_EQ(run.exit_code, kExitUsage);
  EXPECT_NE(run.err.find("unknown step 'spin': current-offset, direction, range, index, friction, gravity"),
            std::string::npos)
      << run.err;
  run = RunTool({"--dir", dir, "--can", "can0", "--emulated", "3", "scan"});
  EXPECT_EQ(run.exit_code, kExitUsage);
  EXPECT_NE(run.err.find("choose one of --can, --udp and --emulated"), std::string::npos) << run.err;
  run = RunTool({"--dir", dir, "restore", "1", "--slot", "C"});
  EXPECT_EQ(run.exit_code, kExitUsage);
  EXPECT_FALSE(std::filesystem::exists(dir)) << "something was written";
}

TEST(CalibrateBadInput, NoArmOnTheBusIsSaidAndOnlyTheBusLogIsWritten) {
  const std::string dir = testing::FreshDir("no-arm");
  const std::uint16_t base = FreeBasePort();
  ASSERT_NE(base, 0);
  const auto scan = RunTool({"--udp-base-port", std::to_string(base), "--dir", dir, "--json", "scan"});
  EXPECT_EQ(scan.exit_code, kExitNoArm);
  EXPECT_EQ(scan.json()["error"]["message"], "no arm answered on UDP 127.0.0.1:" + std::to_string(base));
  const auto cal = RunTool({"--udp-base-port", std::to_string(base), "--dir", dir, "--yes", "calibrate", "2"});
  EXPECT_EQ(cal.exit_code, kExitNoArm);
  EXPECT_NE(cal.err.find("arm 2: no answer from node 2 on UDP 127.0.0.1:" + std::to_string(base + 2) +
                         " (vesica-armsim --node-id 2) (is the arm powered and on this bus?)"),
            std::string::npos)
      << cal.err;
  EXPECT_EQ(cal.err.find("will move"), std::string::npos) << "prompted with no arm";
  for (const std::string& f : FilesUnder(dir)) EXPECT_TRUE(f.ends_with("/bus.log")) << f;
}

// A node whose firmware predates the calibration session (protocol 1.0), as its UDP peer.
struct OldNode {
  std::unique_ptr<fp::UdpTransport> udp;
  std::atomic<bool> stop{false};
  std::atomic<int> other_requests{0};
  std::thread thread;
  explicit OldNode(std::uint16_t base) {
    std::string error;
    udp = fp::UdpTransport::open({.local_port = base, .remote_port = static_cast<std::uint16_t>(base + 1)}, error);
    thread = std::thread([this] {
      while (!stop) {
        udp->wait(2ms);
        fp::TimedFrame rx;
        while (udp->receive(rx)) {
          fp::Message m;
          if (fp::decode(rx.frame, m) != fp::DecodeError::None) continue;
          if (std::holds_alternative<fp::Hello>(m)) {
            fp::CanFrame f;
            fp::encode(fp::Identity{1, 1, 0, 0, 0, 0x01D}, f);
            udp->send(f, udp->now() + 1ms);
          } else if (!std::holds_alternative<fp::Sync>(m)) {
            ++other_requests;
          }
        }
      }
    });
  }
  ~OldNode() {
    stop = true;
    thread.join();
  }
};

TEST(CalibrateBadInput, ANodeWithAnOlderProtocolMinorIsRefusedBeforeAnythingIsAsked) {
  const std::string dir = testing::FreshDir("old-node");
  const std::uint16_t base = FreeBasePort();
  ASSERT_NE(base, 0);
  OldNode old(base);
  ASSERT_TRUE(old.udp);
  const auto run = RunTool({"--udp-base-port", std::to_string(base), "--dir", dir, "--yes", "calibrate", "1"});
  EXPECT_EQ(run.exit_code, kExitProtocolTooOld);
  EXPECT_NE(run.err.find("arm 1: node 1 speaks protocol 1.0; calibration needs 1.1 (update the arm's firmware); "
                         "nothing was changed"),
            std::string::npos)
      << run.err;
  EXPECT_EQ(old.other_requests.load(), 0) << "a request beyond Hello reached the old node";
  const auto scan = RunTool({"--udp-base-port", std::to_string(base), "--dir", dir, "--json", "scan"});
  EXPECT_EQ(scan.exit_code, kExitOk);  // scan lists what it finds, an old node too
  const nlohmann::json arm1 = scan.json()["arms"][0];
  EXPECT_TRUE(arm1["found"].get<bool>());
  EXPECT_EQ(arm1["error"]["name"], "protocol_too_old");
  for (const std::string& f : FilesUnder(dir)) EXPECT_TRUE(f.ends_with("/bus.log")) << f;
}

TEST(CalibrateBadInput, AStoredImageWithABadCrcOrNotACalibrationChangesNothing) {
  const std::string dir = testing::FreshDir("bad-image");
  CalibrateOnce(dir);
  const std::string flash_file = dir + "/emulated/seed-5-arm-1.flash";
  const auto flash = ReadBytes(flash_file);
  const auto files = FilesUnder(dir);
  const std::string good = dir + "/images/serial-5E51CA01-gen-1.vcal";
  auto bytes = ReadBytes(good);
  ASSERT_EQ(bytes.size(), fp::slot::kSize);  // image layout 2

  bytes[100] ^= 0x01;  // one bit in the parameter image
  const std::string corrupt = testing::FreshDir("bad-image-files") + "-corrupt.vcal";
  std::ofstream(corrupt, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                               static_cast<std::streamsize>(bytes.size()));
  auto run = RunTool({"--emulated", "5", "--dir", dir, "restore", "1", "--file", corrupt});
  EXPECT_EQ(run.exit_code, kExitStorage);
  EXPECT_NE(run.err.find(corrupt + ": corrupt (bad CRC); nothing was written"), std::string::npos) << run.err;

  const std::string text = corrupt + ".txt";
  std::ofstream(text) << "yaw offset 0.1\n";
  run = RunTool({"--emulated", "5", "--dir", dir, "--json", "restore", "1", "--file", text});
  EXPECT_EQ(run.exit_code, kExitStorage);
  EXPECT_EQ(run.json()["error"]["message"],
            text + " is not a Vesica calibration image (no VCS1 header); nothing was written");

  const std::string truncated = corrupt + ".short";
  std::ofstream(truncated, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), 200);
  run = RunTool({"--emulated", "5", "--dir", dir, "restore", "1", "--file", truncated});
  EXPECT_EQ(run.exit_code, kExitStorage);
  EXPECT_NE(run.err.find("(200 bytes, a slot has 360 (layout 2) or 320 (layout 1))"), std::string::npos) << run.err;

  run = RunTool({"--emulated", "5", "--dir", dir, "restore", "1", "--file", corrupt + ".missing"});
  EXPECT_EQ(run.exit_code, kExitIo);
  EXPECT_NE(run.err.find("cannot read " + corrupt + ".missing"), std::string::npos) << run.err;

  EXPECT_EQ(ReadBytes(flash_file), flash) << "the arm's flash changed";
  EXPECT_EQ(FilesUnder(dir), files) << "a file was written";
}

TEST(CalibrateBadInput, ACorruptSlotIsNamedInInfoAndNotRestored) {
  const std::string dir = testing::FreshDir("corrupt-slot");
  CalibrateOnce(dir);  // slot A, generation 1
  auto second = RunTool({"--emulated", "5", "--dir", dir, "--yes", "--quiet", "calibrate", "1", "--step", "gravity"});
  ASSERT_EQ(second.exit_code, 0) << second.err;  // slot B, generation 2, in use
  // A bit of slot A's parameter image flips in the flash (slot A at 0, its image after 24 bytes).
  const std::string flash_file = dir + "/emulated/seed-5-arm-1.flash";
  auto flash = ReadBytes(flash_file);
  flash[40] ^= 0x10;
  std::ofstream(flash_file, std::ios::binary)
      .write(reinterpret_cast<const char*>(flash.data()), static_cast<std::streamsize>(flash.size()));
  const auto info = RunTool({"--emulated", "5", "--dir", dir, "info", "1"});
  ASSERT_EQ(info.exit_code, kExitOk) << info.err;
  EXPECT_NE(info.out.find("  slot A: corrupt (bad CRC)\n"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("  slot B: ok, generation 2 (in use)\n"), std::string::npos) << info.out;
  const auto restore = RunTool({"--emulated", "5", "--dir", dir, "restore", "1", "--slot", "A"});
  EXPECT_EQ(restore.exit_code, kExitStorage);
  EXPECT_NE(restore.err.find("arm 1: slot A is corrupt (bad CRC); nothing was written"), std::string::npos)
      << restore.err;
  EXPECT_EQ(ReadBytes(flash_file), flash) << "the arm's flash changed";
}

TEST(CalibrateBadInput, CtrlCMidStepLeavesTheArmOnItsStoredCalibrationAndWritesNoReport) {
  const std::string dir = testing::FreshDir("sigint");
  CalibrateOnce(dir);
  const std::string flash_file = dir + "/emulated/seed-5-arm-1.flash";
  const auto flash = ReadBytes(flash_file);
  const auto images = FilesUnder(dir + "/images");
  const auto sessions_before = FilesUnder(dir + "/sessions");
  // Not a terminal: progress comes as lines; Ctrl-C once the range step has begun.
  const auto run = RunTool({"--emulated", "5", "--dir", dir, "--yes", "calibrate", "1"}, "", "arm 1 range: 0%");
  ASSERT_TRUE(run.interrupted) << run.err;
  EXPECT_EQ(run.exit_code, kExitAborted) << run.err;
  EXPECT_NE(run.err.find("arm 1: calibration aborted by the user; the stored calibration is in force"),
            std::string::npos)
      << run.err;
  EXPECT_EQ(ReadBytes(flash_file), flash) << "the arm's flash changed";
  EXPECT_EQ(FilesUnder(dir + "/images"), images);
  // The session kept its bus log and nothing else.
  std::vector<std::string> added;
  for (const std::string& f : FilesUnder(dir + "/sessions"))
    if (std::find(sessions_before.begin(), sessions_before.end(), f) == sessions_before.end()) added.push_back(f);
  ASSERT_EQ(added.size(), 1u);
  EXPECT_TRUE(added[0].ends_with("/bus.log")) << added[0];
  const auto info = RunTool({"--emulated", "5", "--dir", dir, "--json", "info", "1"});
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_EQ(info.json()["node"]["active_slot"], "A");
  EXPECT_EQ(info.json()["node"]["slots"][0]["generation"], 1);
  EXPECT_EQ(info.json()["node"]["calibration_date_s"], 1790000000);
  EXPECT_EQ(info.json()["node"]["latched_fault"], "none");
}

TEST(CalibrateBadInput, ADeclinedPromptMovesNothing) {
  const std::string dir = testing::FreshDir("declined");
  const auto run = RunTool({"--emulated", "5", "--dir", dir, "calibrate", "1"}, "n\n");
  EXPECT_EQ(run.exit_code, kExitAborted);
  EXPECT_NE(run.err.find("arm 1 (node 1, serial 0x5E51CA01) will move:\n  - encoder direction:"), std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("continue? [y/N]"), std::string::npos);
  EXPECT_NE(run.err.find("arm 1: not confirmed; nothing moved, nothing was written"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace vesica::app::calibrate
