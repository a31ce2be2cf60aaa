// The trainer's arm bridge (Session > Input > Haptic arms): the default scenario gets the emulated
// arms, a link that cannot open is an error naming the port and the reason, the shipped arms
// scenario connects to two vesica-armsim processes, and an arm whose process is restarted comes
// back as "ok" without reopening anything.
#include "app/session/arm_bridge.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <stdexcept>
#include <thread>

#include "app/scenario/scenario_loader.h"
#include "armsim_process.h"

namespace vesica::app {
namespace {

using namespace std::chrono_literals;

Scenario Load(const char* name) { return LoadScenario(std::string(VESICA_SOURCE_DIR "/data/scenarios/") + name); }

/// The haptic thread: ticks the bridge at 1 kHz while alive.
class TickThread {
 public:
  explicit TickThread(ArmBridge& bridge)
      : thread_([this, &bridge] {
          while (!stop_.load()) {
            bridge.Tick();
            std::this_thread::sleep_for(1ms);
          }
        }) {}
  ~TickThread() {
    stop_.store(true);
    thread_.join();
  }

 private:
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

std::string WaitForLine(const ArmBridge& bridge, std::size_t arm, const std::string& want, int max_ms) {
  std::string text;
  for (int i = 0; i <= max_ms / 10; ++i) {
    text = bridge.Reports().at(arm).text;
    if (text == want) break;
    std::this_thread::sleep_for(10ms);
  }
  return text;
}

std::vector<std::string> ArmsimArgs(int base, int node) {
  const int port = base + 2 * (node - 1);
  return {"--node-id",     std::to_string(node),
          "--local-port",  std::to_string(port),
          "--remote-port", std::to_string(port + 1),
          "--log-level",   "warn",
          "--hand",        "figure8"};
}

TEST(ArmBridgeTest, ShippedArmsScenarioNamesBothArms) {
  const Scenario s = Load("cholecystectomy-arms.toml");
  ASSERT_TRUE(ArmBridge::ScenarioUsesArms(s));
  ASSERT_EQ(s.instruments.size(), 2u);
  for (const InstrumentConfig& c : s.instruments) {
    EXPECT_EQ(c.input, InputKind::kEmulatedArm) << c.name;
    EXPECT_EQ(c.can_node_id, c.kind == InstrumentKind::kGrasper ? 1 : 2) << c.name;
  }
  // The same task as the default scenario: recordings replay in both, sessions share a curve.
  EXPECT_EQ(s.name, Load("cholecystectomy.toml").name);
}

/// The file from its [scenario] table on, without the lines the arms scenario changes.
std::string WithoutInputs(const char* name) {
  std::ifstream in(std::string(VESICA_SOURCE_DIR "/data/scenarios/") + name);
  std::string line, out;
  bool started = false;
  while (std::getline(in, line)) {
    started = started || line == "[scenario]";
    const bool changed =
        line.starts_with("input =") || line.starts_with("can_node_id =") || line.starts_with("description =");
    if (started && !changed) out += line + "\n";
  }
  return out;
}

// The arms scenario is the default one with arms: the same organs, ports, camera and settings
// (the format has no way to include one scenario in another, so a change to the default must be
// made here too; this test says when it was not).
TEST(ArmBridgeTest, ShippedArmsScenarioIsTheDefaultOneWithArms) {
  const std::string arms = WithoutInputs("cholecystectomy-arms.toml");
  ASSERT_FALSE(arms.empty());
  EXPECT_EQ(arms, WithoutInputs("cholecystectomy.toml"))
      << "data/scenarios/cholecystectomy-arms.toml differs from cholecystectomy.toml beyond its instruments' input";
}

// Session > Input > Haptic arms on the default scenario (keyboard instruments): the bridge drives
// the emulated arms (node 1 grasper, node 2 hook) and says where it waits for them, instead of
// leaving both instruments without input.
TEST(ArmBridgeTest, DefaultScenarioGetsTheEmulatedArmsAndSaysWhereItWaits) {
  const int base = device::testing::FreeArmBasePort();
  ASSERT_NE(base, 0);
  ArmBridgeOptions options;
  options.udp_base_port = base;
  ArmBridge bridge(Load("cholecystectomy.toml"), options);
  const auto devices = bridge.devices();
  EXPECT_NE(devices[0], nullptr);
  EXPECT_NE(devices[1], nullptr);
  bridge.Tick();
  const auto reports = bridge.Reports();
  ASSERT_EQ(reports.size(), 2u);
  EXPECT_EQ(reports[0].text,
            "left arm: waiting for node 1 on UDP 127.0.0.1:" + std::to_string(base) + " (vesica-armsim --node-id 1)");
  EXPECT_EQ(reports[1].text, "right arm: waiting for node 2 on UDP 127.0.0.1:" + std::to_string(base + 2) +
                                 " (vesica-armsim --node-id 2)");
  EXPECT_FALSE(bridge.AllOk());
}

// A port another program holds: an exception naming the instrument, the port and the system's
// reason, never an arm-less bridge.
TEST(ArmBridgeTest, LinkThatCannotOpenIsAnErrorNamingThePortAndTheReason) {
  const int base = device::testing::FreeArmBasePort();
  ASSERT_NE(base, 0);
  std::string error;
  auto squatter = fp::UdpTransport::open({.local_port = static_cast<std::uint16_t>(base + 1)}, error);
  ASSERT_TRUE(squatter) << error;
  ArmBridgeOptions options;
  options.udp_base_port = base;
  try {
    ArmBridge bridge(Load("cholecystectomy-arms.toml"), options);
    FAIL() << "the bridge opened although UDP port " << base + 1 << " is taken";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("instrument 'grasper'"), std::string::npos) << what;
    EXPECT_NE(what.find("UDP port " + std::to_string(base + 1)), std::string::npos) << what;
    EXPECT_NE(what.find("Address already in use"), std::string::npos) << what;
  }
  options.udp_base_port = 65535;
  EXPECT_THROW(ArmBridge(Load("cholecystectomy-arms.toml"), options), std::invalid_argument);
  options.udp_base_port = base;
  options.node_watchdog = 150ms;  // the node would refuse it and keep its 3 ms
  EXPECT_THROW(ArmBridge(Load("cholecystectomy-arms.toml"), options), std::invalid_argument);
}

// Both arms connect; the right arm's process is killed ("link lost") and started again: it is
// "ok" again without reopening the bridge or asking the user.
TEST(ArmBridgeTest, ArmsimRestartReturnsTheArmToOk) {
  const int base = device::testing::FreeArmBasePort();
  ASSERT_NE(base, 0);
  ArmBridgeOptions options;
  options.udp_base_port = base;
  ArmBridge bridge(Load("cholecystectomy-arms.toml"), options);
  device::testing::ArmsimProcess left;
  ASSERT_TRUE(left.Start(VESICA_ARMSIM_PATH, ArmsimArgs(base, 1)));
  TickThread ticking(bridge);
  {
    device::testing::ArmsimProcess right;
    ASSERT_TRUE(right.Start(VESICA_ARMSIM_PATH, ArmsimArgs(base, 2)));
    EXPECT_EQ(WaitForLine(bridge, 0, "left arm: ok", 5000), "left arm: ok");
    EXPECT_EQ(WaitForLine(bridge, 1, "right arm: ok", 5000), "right arm: ok");
  }  // SIGTERM: the right arm's process is gone
  EXPECT_EQ(WaitForLine(bridge, 1, "right arm: link lost", 3000), "right arm: link lost");
  device::testing::ArmsimProcess right_again;
  ASSERT_TRUE(right_again.Start(VESICA_ARMSIM_PATH, ArmsimArgs(base, 2)));
  EXPECT_EQ(WaitForLine(bridge, 1, "right arm: ok", 5000), "right arm: ok");
  EXPECT_EQ(bridge.Reports().at(0).text, "left arm: ok");
  EXPECT_EQ(bridge.Reports().at(1).link_losses, 1u);
}

}  // namespace
}  // namespace vesica::app
