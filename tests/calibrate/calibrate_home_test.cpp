// Homing after power-up over UDP (protocol 1.4), as a technician and the trainer meet it:
// vesica-armsim --moved-while-off 0.7 is an arm switched off, moved 0.7 rad (70 mm) by hand and
// switched on again. `vesica-calibrate home 1` finds its frame again (the corrections are the move,
// to an encoder count or so); Ctrl-C mid-home leaves it disabled and not homed; a single step
// of calibrate is refused on it until it is homed; a 1.3 node cannot be homed (exit code 4). The
// trainer's bridge homes it at connection, its status line saying "homing", then enables it.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <thread>

#include "../device/armsim_process.h"
#include "app/calibrate/exit_codes.h"
#include "device/arm_supervisor.h"
#include "device/can_arm.h"
#include "firmware_protocol/emulator/arm_ground_truth.h"
#include "firmware_protocol/emulator/arm_plant_parameters.h"
#include "firmware_protocol/transport/udp_transport.h"
#include "tool_process.h"

namespace vesica::app::calibrate {
namespace {

using namespace std::chrono_literals;
using testing::RunTool;
using testing::ToolRun;
namespace emu = fp::emulator;

constexpr double kDepth_m = 0.12;  // vesica-armsim's default --depth-mm: where it was calibrated

// The move vesica-armsim --moved-while-off 0.7 --moved-seed SEED made, per joint (yaw, pitch, insertion).
std::array<double, 3> MoveOf(std::uint64_t seed) {
  const emu::Joint4 q0{0.0, 0.0, 0.0, kDepth_m};
  const emu::Joint4 q = emu::MovedWhileOff(emu::ArmPlantParameters::Nominal(), q0, 0.7, seed);
  return {q[0] - q0[0], q[1] - q0[1], q[3] - q0[3]};
}

// One encoder count of the nominal arm at the joint, rad or m.
double Count(int j) { return 2.0 * M_PI / 2048.0 / (j < 2 ? 14.0 : 100.0); }

struct MovedArm {
  int base = 0;
  device::testing::ArmsimProcess armsim;
  bool Start(const std::vector<std::string>& extra) {
    base = device::testing::FreeArmBasePort();
    if (base == 0) return false;
    std::vector<std::string> args{"--node-id", "1", "--local-port", std::to_string(base), "--log-level", "warn"};
    args.insert(args.end(), extra.begin(), extra.end());
    return armsim.Start(VESICA_ARMSIM_PATH, args);
  }
  ToolRun Tool(const std::string& dir, std::vector<std::string> args, const std::string& interrupt_on = "") {
    args.insert(args.begin(), {"--udp-base-port", std::to_string(base), "--dir", dir});
    ToolRun run;
    // The arm boots within a moment: try again while nothing answers.
    for (int attempt = 0; attempt < 20; ++attempt) {
      run = RunTool(args, "", interrupt_on);
      if (run.exit_code != kExitNoArm) break;
    }
    return run;
  }
};

TEST(CalibrateHome, HomesAnArmMovedWhileOffToTheMove) {
  MovedArm arm;
  ASSERT_TRUE(arm.Start({"--moved-while-off", "0.7", "--moved-seed", "3"}));
  const std::string dir = testing::FreshDir("home-udp");
  // Not homed: a single step would work in the wrong frame, so it is refused before anything moves.
  const ToolRun step = arm.Tool(dir, {"--yes", "--json", "calibrate", "1", "--step", "friction"});
  EXPECT_EQ(step.exit_code, kExitFailed) << step.err;
  EXPECT_NE(step.out.find("is not homed since power-up"), std::string::npos) << step.out;
  EXPECT_NE(step.out.find("vesica-calibrate home 1"), std::string::npos) << step.out;

  const ToolRun run = arm.Tool(dir, {"--yes", "--json", "home", "1"});
  ASSERT_EQ(run.exit_code, kExitOk) << run.err << run.out;
  const nlohmann::json j = run.json();
  EXPECT_TRUE(j["homed"].get<bool>());
  EXPECT_FALSE(j["was_homed"].get<bool>());
  ASSERT_EQ(j["joints"].size(), 3u);
  const std::array<double, 3> move = MoveOf(3);
  for (int k = 0; k < 3; ++k) {
    SCOPED_TRACE(j["joints"][k]["joint"].get<std::string>());
    EXPECT_NEAR(j["joints"][k]["correction"].get<double>(), move[k], 2 * Count(k));
  }
  // Homed, it stays homed: a second run (in the human form) finds no move left to correct.
  const ToolRun again = arm.Tool(dir, {"--yes", "home", "1"});
  ASSERT_EQ(again.exit_code, kExitOk) << again.err;
  EXPECT_NE(again.out.find("arm 1 (node 1, serial 0x5E51CA01): homed, "), std::string::npos) << again.out;
  const char* names[3] = {"  yaw       moved ", "  pitch     moved ", "  insertion moved "};
  for (int k = 0; k < 3; ++k) {
    const auto at = again.out.find(names[k]);
    ASSERT_NE(at, std::string::npos) << again.out;
    double correction = 1.0;
    ASSERT_EQ(std::sscanf(again.out.c_str() + at + std::strlen(names[k]), "%lf", &correction), 1) << again.out;
    EXPECT_NEAR(correction, 0.0, 2 * Count(k)) << names[k];
  }
}

TEST(CalibrateHome, CtrlCMidHomeLeavesTheArmNotHomed) {
  MovedArm arm;
  ASSERT_TRUE(arm.Start({"--moved-while-off", "0.7"}));
  const std::string dir = testing::FreshDir("home-abort");
  const ToolRun run = arm.Tool(dir, {"--yes", "--json", "home", "1"}, "arm 1 homing");
  EXPECT_TRUE(run.interrupted);
  ASSERT_EQ(run.exit_code, kExitAborted) << run.err << run.out;
  EXPECT_EQ(run.json()["error"]["reason"], "abort_requested");
  EXPECT_NE(run.json()["error"]["message"].get<std::string>().find("the arm is disabled and not homed"),
            std::string::npos);
  // Still not homed: a single step is refused.
  const ToolRun step = arm.Tool(dir, {"--yes", "--json", "calibrate", "1", "--step", "friction"});
  EXPECT_EQ(step.exit_code, kExitFailed) << step.err;
  EXPECT_NE(step.out.find("is not homed since power-up"), std::string::npos) << step.out;
}

TEST(CalibrateHome, ANodeOfProtocol13IsRefusedAndNothingMoves) {
  MovedArm arm;
  ASSERT_TRUE(arm.Start({"--firmware-minor", "3"}));
  const std::string dir = testing::FreshDir("home-old");
  const ToolRun run = arm.Tool(dir, {"--yes", "--json", "home", "1"});
  ASSERT_EQ(run.exit_code, kExitProtocolTooOld) << run.err << run.out;
  EXPECT_EQ(run.json()["error"]["name"], "protocol_too_old");
  EXPECT_NE(run.json()["error"]["message"].get<std::string>().find(
                "speaks protocol 1.3: homing needs 1.4 (update the arm's firmware)"),
            std::string::npos)
      << run.out;
  EXPECT_EQ(run.err.find("homing:"), std::string::npos) << "nothing may move: " << run.err;
}

// The trainer's bridge at connection: the arm says it is not homed, the bridge homes it (its
// status line says so, with the progress), then enables it. The corrections are the move.
TEST(BridgeHoming, HomesAnArmMovedWhileOffAtConnectionThenEnablesIt) {
  MovedArm arm;
  ASSERT_TRUE(arm.Start({"--moved-while-off", "0.7", "--moved-seed", "5"}));
  std::string error;
  auto host = fp::UdpTransport::open(
      {.local_port = static_cast<std::uint16_t>(arm.base + 1), .remote_port = static_cast<std::uint16_t>(arm.base)},
      error);
  ASSERT_TRUE(host) << error;
  device::CanArmConfig config;
  config.node_watchdog_timeout = 50ms;  // a loaded shared host, as the trainer's bridge
  config.loss_timeout = 500ms;
  device::CanArm can_arm(*host, config);
  ASSERT_EQ(can_arm.Open(), device::DeviceStatus::kConnecting);
  device::ArmSupervisorConfig sc;
  sc.name = "left arm";
  device::ArmSupervisor supervisor(can_arm, sc);
  std::vector<std::string> lines;
  auto next = std::chrono::steady_clock::now();
  const auto until = next + 60s;
  while (std::chrono::steady_clock::now() < until && can_arm.Status() != device::DeviceStatus::kOk) {
    can_arm.Tick();
    supervisor.Tick(host->now());
    const std::string line = supervisor.Report().text;
    if (lines.empty() || lines.back() != line) lines.push_back(line);
    next += 1ms;
    std::this_thread::sleep_until(next);
  }
  std::string all;
  for (const std::string& l : lines) all += l + "\n";
  ASSERT_EQ(can_arm.Status(), device::DeviceStatus::kOk) << all << can_arm.homing_problem();
  EXPECT_EQ(can_arm.homing_count(), 1u);
  EXPECT_NE(all.find("left arm: homing 0%"), std::string::npos) << all;
  EXPECT_NE(all.find("left arm: homing 90%"), std::string::npos) << all;  // every joint found, going back
  EXPECT_EQ(supervisor.Report().text, "left arm: ok");
  const device::calibration::HomingResult r = can_arm.last_homing();
  ASSERT_TRUE(r.homed) << r.message;
  const std::array<double, 3> move = MoveOf(5);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(r.correction[k], move[k], 2 * Count(k)) << "joint " << k;
  can_arm.Close();
}

}  // namespace
}  // namespace vesica::app::calibrate

namespace vesica::app::calibrate {
namespace {

// The trainer closing while the bridge homes an arm (Close from another thread): the run is
// stopped, the node ends its session, the arm is left disabled and not homed.
TEST(BridgeHoming, ClosedMidHomeLeavesTheArmNotHomed) {
  MovedArm arm;
  ASSERT_TRUE(arm.Start({"--moved-while-off", "0.7"}));
  std::string error;
  auto host = fp::UdpTransport::open(
      {.local_port = static_cast<std::uint16_t>(arm.base + 1), .remote_port = static_cast<std::uint16_t>(arm.base)},
      error);
  ASSERT_TRUE(host) << error;
  device::CanArmConfig config;
  config.node_watchdog_timeout = 50ms;
  config.loss_timeout = 500ms;
  device::CanArm can_arm(*host, config);
  ASSERT_EQ(can_arm.Open(), device::DeviceStatus::kConnecting);
  auto next = std::chrono::steady_clock::now();
  const auto until = next + 20s;
  while (std::chrono::steady_clock::now() < until && !(can_arm.homing() && can_arm.homing_fraction() > 0.0)) {
    can_arm.Tick();
    next += 1ms;
    std::this_thread::sleep_until(next);
  }
  ASSERT_TRUE(can_arm.homing()) << can_arm.last_error();
  can_arm.Close();
  EXPECT_FALSE(can_arm.homing());
  host.reset();  // the tool takes the bridge's port
  const std::string dir = testing::FreshDir("home-closed");
  const ToolRun step = arm.Tool(dir, {"--yes", "--json", "calibrate", "1", "--step", "friction"});
  EXPECT_EQ(step.exit_code, kExitFailed) << step.err;
  EXPECT_NE(step.out.find("is not homed since power-up"), std::string::npos) << step.out;
}

}  // namespace
}  // namespace vesica::app::calibrate
