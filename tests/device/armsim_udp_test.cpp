// The same bridge against vesica-armsim in its own process, over CAN-over-UDP on loopback.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "armsim_process.h"
#include "device/bridge_loop.h"
#include "device/can_arm.h"

namespace vesica::device {
namespace {

using namespace std::chrono_literals;

TEST(ArmsimUdpTest, SeparateProcessEmulatorWorksWithTheSameBridge) {
  const std::uint16_t arm_port = testing::FreeUdpPort();
  std::string error;
  auto host = fp::UdpTransport::open({.local_port = 0, .remote_port = arm_port}, error);
  ASSERT_TRUE(host) << error;
  ASSERT_NE(arm_port, 0);

  testing::ArmsimProcess armsim;
  ASSERT_TRUE(armsim.Start(VESICA_ARMSIM_PATH,
                           {"--local-port", std::to_string(arm_port), "--remote-port",
                            std::to_string(host->local_port()), "--duration-s", "4", "--report",
                            "--log-level", "warn"}));

  // This shared build machine gives the 1 kHz thread no real-time guarantee (several ms gaps
  // under load): a 50 ms node watchdog and 100 ms loss timeout instead of 3 ms / 10 ms.
  CanArmConfig config;
  config.node_watchdog_timeout = 50ms;
  config.loss_timeout = 100ms;
  CanArm arm(*host, config);
  ASSERT_EQ(arm.Open(), DeviceStatus::kConnecting);
  BridgeLoop loop(arm);
  loop.Start();
  DeviceStatus status = DeviceStatus::kConnecting;
  for (int i = 0; i < 250 && status != DeviceStatus::kOk; ++i) {
    std::this_thread::sleep_for(10ms);
    status = arm.Status();
  }
  ASSERT_EQ(status, DeviceStatus::kOk) << ToString(status) << " " << arm.last_error();
  const Eigen::Vector3d f(0.8, -0.4, 1.2);
  arm.SetTipForce(f);

  std::string report;
  const int rc = armsim.Finish(&report);  // the arm runs 4 s, then reports and exits
  loop.Stop();
  ASSERT_EQ(rc, 0) << report;

  double h[3], a[3];
  ASSERT_EQ(std::sscanf(report.c_str(), "hand_force_N=%lf,%lf,%lf actuator_force_N=%lf,%lf,%lf", &h[0], &h[1],
                        &h[2], &a[0], &a[1], &a[2]),
            6)
      << report;
  const Eigen::Vector3d felt(h[0], h[1], h[2]);
  EXPECT_LT((felt - f).norm(), 0.05 * f.norm()) << "felt " << felt.transpose() << " report: " << report;
  const auto period = arm.loop_period();
  EXPECT_NE(report.find("state=operational"), std::string::npos)
      << report << " host loop period p99 " << period.p99_ns << " ns, max " << period.max_ns << " ns";

  const auto rt = arm.round_trip();
  EXPECT_GT(rt.count, 1000u);        // about one answered command per millisecond
  EXPECT_LT(rt.p50_ns, 5e6);         // loopback UDP + a 100 us node tick
  EXPECT_EQ(arm.decode_errors().total(), 0u);
}

// vesica-armsim --uncalibrated: a board nobody calibrated. The bridge reads its blank slots and
// never enables it; the arm reports pre-operational and disabled at its end.
TEST(ArmsimUdpTest, UncalibratedArmIsNeverEnabled) {
  const std::uint16_t arm_port = testing::FreeUdpPort();
  std::string error;
  auto host = fp::UdpTransport::open({.local_port = 0, .remote_port = arm_port}, error);
  ASSERT_TRUE(host) << error;
  ASSERT_NE(arm_port, 0);
  testing::ArmsimProcess armsim;
  ASSERT_TRUE(armsim.Start(VESICA_ARMSIM_PATH,
                           {"--local-port", std::to_string(arm_port), "--remote-port",
                            std::to_string(host->local_port()), "--duration-s", "2", "--report", "--uncalibrated",
                            "--log-level", "warn"}));
  CanArmConfig config;
  config.node_watchdog_timeout = 50ms;
  config.loss_timeout = 100ms;
  CanArm arm(*host, config);
  ASSERT_EQ(arm.Open(), DeviceStatus::kConnecting);
  BridgeLoop loop(arm);
  loop.Start();
  for (int i = 0; i < 150 && arm.Status() != DeviceStatus::kNotCalibrated; ++i) std::this_thread::sleep_for(10ms);
  EXPECT_EQ(arm.Status(), DeviceStatus::kNotCalibrated) << ToString(arm.Status()) << " " << arm.last_error();
  EXPECT_EQ(arm.calibration_problem(), "slot A: blank, slot B: blank");
  arm.SetTipForce(Eigen::Vector3d(0.8, -0.4, 1.2));
  std::string report;
  const int rc = armsim.Finish(&report);
  loop.Stop();
  ASSERT_EQ(rc, 0) << report;
  EXPECT_NE(report.find("actuator_force_N=0.000000,0.000000,0.000000"), std::string::npos) << report;
  EXPECT_NE(report.find("state=pre-operational"), std::string::npos) << report;
}

// The arm process dies mid-session (vanished device): the bridge reports the loss and keeps
// running; a new arm process on the same port is picked up again through a fresh handshake.
TEST(ArmsimUdpTest, VanishedArmProcessIsReportedAndReplacementReconnects) {
  const std::uint16_t arm_port = testing::FreeUdpPort();
  std::string error;
  auto host = fp::UdpTransport::open({.local_port = 0, .remote_port = arm_port}, error);
  ASSERT_TRUE(host) << error;
  const std::vector<std::string> args{"--local-port", std::to_string(arm_port), "--remote-port",
                                      std::to_string(host->local_port()), "--log-level", "warn"};
  CanArmConfig config;
  config.node_watchdog_timeout = 50ms;
  config.loss_timeout = 100ms;
  CanArm arm(*host, config);
  arm.Open();
  BridgeLoop loop(arm);
  loop.Start();
  auto wait_for = [&](DeviceStatus want, int max_ms) {
    for (int i = 0; i < max_ms / 10 && arm.Status() != want; ++i) std::this_thread::sleep_for(10ms);
    return arm.Status();
  };
  {
    testing::ArmsimProcess first;
    ASSERT_TRUE(first.Start(VESICA_ARMSIM_PATH, args));
    ASSERT_EQ(wait_for(DeviceStatus::kOk, 3000), DeviceStatus::kOk) << arm.last_error();
    arm.SetTipForce(Eigen::Vector3d(0.3, 0.0, 0.5));
    std::this_thread::sleep_for(200ms);
  }  // SIGTERM: the arm process is gone
  EXPECT_EQ(wait_for(DeviceStatus::kLinkLost, 2000), DeviceStatus::kLinkLost);
  EXPECT_EQ(arm.link_loss_count(), 1u);
  EXPECT_EQ(arm.last_command().current_A, Eigen::Vector3d::Zero());

  testing::ArmsimProcess second;
  ASSERT_TRUE(second.Start(VESICA_ARMSIM_PATH, args));
  EXPECT_EQ(wait_for(DeviceStatus::kOk, 3000), DeviceStatus::kOk) << ToString(arm.Status()) << " " << arm.last_error();
  EXPECT_EQ(arm.link_restore_count(), 1u);
  loop.Stop();
}

// Runs vesica-armsim with `hand_args` against a bridge for `seconds`, and returns the tip
// positions the bridge measured (every 10 ms once the arm was ok).
std::vector<Eigen::Vector3d> TipsMeasuredWithHand(const std::vector<std::string>& hand_args, double seconds) {
  const std::uint16_t arm_port = testing::FreeUdpPort();
  std::string error;
  auto host = fp::UdpTransport::open({.local_port = 0, .remote_port = arm_port}, error);
  EXPECT_TRUE(host) << error;
  if (!host) return {};
  std::vector<std::string> args{"--local-port", std::to_string(arm_port), "--remote-port",
                                std::to_string(host->local_port()), "--log-level", "warn"};
  args.insert(args.end(), hand_args.begin(), hand_args.end());
  testing::ArmsimProcess armsim;
  EXPECT_TRUE(armsim.Start(VESICA_ARMSIM_PATH, args));
  CanArmConfig config;
  config.node_watchdog_timeout = 50ms;
  config.loss_timeout = 100ms;
  CanArm arm(*host, config);
  arm.Open();
  BridgeLoop loop(arm);
  loop.Start();
  for (int i = 0; i < 300 && arm.Status() != DeviceStatus::kOk; ++i) std::this_thread::sleep_for(10ms);
  EXPECT_EQ(arm.Status(), DeviceStatus::kOk) << ToString(arm.Status()) << " " << arm.last_error();
  std::vector<Eigen::Vector3d> tips;
  for (int i = 0; i < static_cast<int>(seconds * 100); ++i) {
    std::this_thread::sleep_for(10ms);
    if (arm.Status() == DeviceStatus::kOk) tips.push_back(arm.GetToolState().p_BTip_B);
  }
  loop.Stop();
  return tips;
}

double Range(const std::vector<Eigen::Vector3d>& tips, const std::function<double(const Eigen::Vector3d&)>& f) {
  double lo = 1e9, hi = -1e9;
  for (const Eigen::Vector3d& p : tips) {
    lo = std::min(lo, f(p));
    hi = std::max(hi, f(p));
  }
  return tips.empty() ? 0.0 : hi - lo;
}

// `--hand figure8`: the scripted hand moves the emulated arm and the bridge sees the instrument
// trace the figure (25 mm to each side by default).
TEST(ArmsimUdpTest, FigureEightHandMovesTheArmTheBridgeMeasures) {
  const auto tips = TipsMeasuredWithHand({"--hand", "figure8", "--figure8-period-s", "2"}, 3.0);
  ASSERT_GT(tips.size(), 100u);
  EXPECT_GT(Range(tips, [](const Eigen::Vector3d& p) { return p.x(); }), 0.04);
  EXPECT_GT(Range(tips, [](const Eigen::Vector3d& p) { return p.y(); }), 0.015);
}

// `--hand recording FILE`: the right hand of the committed dissection. The arm starts parked at
// 120 mm and the recording's hook starts at 50 mm: the bridge sees the insertion follow.
TEST(ArmsimUdpTest, RecordedHandMovesTheArmTheBridgeMeasures) {
  const auto tips = TipsMeasuredWithHand(
      {"--side", "right", "--hand", "recording", VESICA_SOURCE_DIR "/data/recordings/dissection.csv"}, 3.0);
  ASSERT_GT(tips.size(), 100u);
  EXPECT_GT(Range(tips, [](const Eigen::Vector3d& p) { return p.norm(); }), 0.04);
  EXPECT_LT(tips.back().norm(), 0.07);  // at the recording's depth after the 2 s lead-in
}

TEST(ArmsimUdpTest, UnreadableRecordingIsANamedErrorAtStart) {
  testing::ArmsimProcess armsim;
  ASSERT_TRUE(armsim.Start(VESICA_ARMSIM_PATH, {"--hand", "recording", "/nonexistent/dissection.csv"}));
  std::string out;
  EXPECT_EQ(armsim.Finish(&out), 2);
  EXPECT_NE(out.find("/nonexistent/dissection.csv"), std::string::npos) << out;
}

}  // namespace
}  // namespace vesica::device
