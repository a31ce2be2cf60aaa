// vesica-calibrate --can on a real SocketCAN stack (vcan0, inside user-mode Linux through
// scripts/uml/run_in_uml.sh): two emulated arms (nodes 1 and 2) on the one interface, as the
// trainer's arms share can0; scan finds both, info reads one, and the bus log names the interface.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <fstream>
#include <thread>

#include "app/calibrate/exit_codes.h"
#include "firmware_protocol/buslog/bus_log_reader.h"
#include "firmware_protocol/emulator/arm_emulator.h"
#include "firmware_protocol/emulator/arm_ground_truth.h"
#include "firmware_protocol/transport/socketcan_transport.h"
#include "tool_process.h"

namespace vesica::app::calibrate {
namespace {

namespace emu = fp::emulator;
using namespace std::chrono_literals;

// One arm on its own socket, stepped in real time on a thread.
struct CanArm {
  std::unique_ptr<fp::SocketCanTransport> can;
  std::unique_ptr<emu::ArmEmulator> arm;
  std::atomic<bool> stop{false};
  std::thread thread;
  CanArm(const std::string& interface, int node) {
    std::string error;
    can = fp::SocketCanTransport::open(fp::SocketCanConfig{.interface = interface, .filters = {}}, error);
    if (!can) return;
    emu::ArmEmulator::Config config;
    config.node_id = static_cast<std::uint8_t>(node);
    config.serial = 0x5E51CA00u + static_cast<std::uint32_t>(node);
    config.tick_period = 500us;  // user-mode Linux is slow: a coarser plant step keeps up
    const emu::ArmGroundTruth truth = emu::RandomArm(static_cast<std::uint64_t>(node));
    arm = std::make_unique<emu::ArmEmulator>(*can, truth.plant, truth.power_up, config);
    thread = std::thread([this] {
      while (!stop) {
        arm->RunUntil(can->now());
        can->wait(500us);
      }
    });
  }
  ~CanArm() {
    stop = true;
    if (thread.joinable()) thread.join();
  }
};

TEST(CalibrateSocketCan, ScanFindsBothArmsOnOneInterfaceAndTheLogNamesIt) {
  const char* env = std::getenv("VESICA_CAN_INTERFACE");
  const std::string interface = env ? env : "vcan0";
  std::string why;
  if (!fp::SocketCanTransport::kernel_supports_can(why)) {
    if (std::getenv("VESICA_REQUIRE_CAN")) FAIL() << "no CAN stack: " << why;
    GTEST_SKIP() << "no CAN stack here (" << why << "); CTest runs this inside user-mode Linux";
  }
  CanArm left(interface, 1), right(interface, 2);
  ASSERT_TRUE(left.arm && right.arm) << "cannot open " << interface;
  std::this_thread::sleep_for(50ms);  // both boot
  const std::string dir = testing::FreshDir("socketcan");
  // The arms come up within a moment: scan until both answer (each try a whole scan).
  testing::ToolRun scan;
  for (int attempt = 0; attempt < 10; ++attempt) {
    scan = testing::RunTool({"--can", interface, "--dir", dir, "--json", "scan"});
    if (scan.exit_code == kExitOk && scan.json()["arms"][0]["found"].get<bool>() &&
        scan.json()["arms"][1]["found"].get<bool>())
      break;
  }
  ASSERT_EQ(scan.exit_code, kExitOk) << scan.err << scan.out;
  const nlohmann::json j = scan.json();
  EXPECT_EQ(j["bus"], "SocketCAN " + interface);
  for (int k = 0; k < 2; ++k) {
    EXPECT_TRUE(j["arms"][k]["found"].get<bool>()) << j.dump(2);
    EXPECT_EQ(j["arms"][k]["node"], k + 1);
    EXPECT_EQ(j["arms"][k]["serial"], 0x5E51CA01u + static_cast<unsigned>(k));
    EXPECT_EQ(j["arms"][k]["protocol"], "1.4");
  }
  std::ifstream log(j["bus_log"].get<std::string>());
  std::vector<fp::BusLogEntry> entries;
  std::string error;
  ASSERT_TRUE(fp::read_bus_log(log, entries, error)) << error;
  EXPECT_EQ(entries.size(), j["bus_log_frames"].get<std::uint64_t>());
  ASSERT_FALSE(entries.empty());
  for (const auto& e : entries) EXPECT_EQ(e.interface, interface);
}

}  // namespace
}  // namespace vesica::app::calibrate
