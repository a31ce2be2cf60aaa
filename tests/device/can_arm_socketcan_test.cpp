// Bridge + emulator session over a real SocketCAN stack (vcan0): both ends in this process, each
// on its own CAN_RAW socket and thread, in real time. Skips with the reason where the kernel has
// no AF_CAN; CTest runs it inside user-mode Linux (scripts/uml/run_in_uml.sh) with candump.
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <thread>

#include <gtest/gtest.h>

#include "device/bridge_loop.h"
#include "device/can_arm.h"
#include "firmware_protocol/emulator/arm_emulator.h"
#include "firmware_protocol/transport/socketcan_transport.h"

namespace vesica::device {
namespace {

using namespace std::chrono_literals;
namespace emu = fp::emulator;

std::string InterfaceName() {
  const char* env = std::getenv("VESICA_CAN_INTERFACE");
  return env ? env : "vcan0";
}

TEST(CanArmSocketCanTest, BridgeAndEmulatorOverVcan) {
  std::string why;
  if (!fp::SocketCanTransport::kernel_supports_can(why)) GTEST_SKIP() << "kernel has no AF_CAN: " << why;
  std::string err;
  fp::SocketCanConfig can;
  can.interface = InterfaceName();
  auto host = fp::SocketCanTransport::open(can, err);
  if (!host) GTEST_SKIP() << "no " << InterfaceName() << ": " << err;
  auto arm_bus = fp::SocketCanTransport::open(can, err);
  ASSERT_TRUE(arm_bus) << err;

  const emu::Joint4 q0{0.1, 0.05, 0.0, 0.12};
  emu::ArmEmulator::Config ec;
  ec.board.park_position = {0.1f, 0.05f, 0.12f};
  ec.tick_period = 200us;  // 5 kHz: less work for a slow virtual machine
  emu::ArmEmulator emulator(*arm_bus, emu::ArmPlantParameters::Nominal(), q0, ec);
  emu::HandTarget hold;
  hold.p_T = emu::TipPosition(q0);
  emulator.plant().SetHandScript(emu::HandScript(hold));
  std::atomic<bool> run{true};
  std::atomic<double> plant_time_s{0.0};  // user-mode Linux can run slower than real time
  std::thread arm_thread([&] {
    while (run.load()) {
      arm_bus->wait(100us);
      emulator.RunUntil(arm_bus->now());
      plant_time_s.store(emulator.plant().time_s());
    }
  });

  CanArmConfig config;  // no real-time guarantee inside user-mode Linux: generous timeouts
  config.node_watchdog_timeout = 50ms;
  config.loss_timeout = 100ms;
  CanArm arm(*host, config);
  arm.Open();
  BridgeLoop loop(arm);
  loop.Start();
  DeviceStatus status = DeviceStatus::kConnecting;
  for (int i = 0; i < 300 && status != DeviceStatus::kOk; ++i) {
    std::this_thread::sleep_for(10ms);
    status = arm.Status();
  }
  const Eigen::Vector3d f(-0.6, 0.4, 1.0);
  arm.SetTipForce(f);
  // 1.5 s of emulated arm time to settle (wall time may be longer under user-mode Linux).
  const double settle_until = plant_time_s.load() + 1.5;
  for (int i = 0; i < 2000 && plant_time_s.load() < settle_until; ++i) std::this_thread::sleep_for(10ms);
  const DeviceStatus end_status = arm.Status();
  run.store(false);  // stop the arm first: its plant state is read below with the force still on
  arm_thread.join();
  loop.Stop();

  ASSERT_EQ(status, DeviceStatus::kOk) << ToString(status) << " " << arm.last_error();
  EXPECT_EQ(end_status, DeviceStatus::kOk);
  const emu::Vec3 felt = emulator.plant().ForceOnHand();
  EXPECT_LT((Eigen::Vector3d(felt[0], felt[1], felt[2]) - f).norm(), 0.05 * f.norm())
      << "felt " << felt[0] << " " << felt[1] << " " << felt[2];
  EXPECT_EQ(emulator.node().latched_fault(), fp::FaultCode::None);
  EXPECT_EQ(arm.decode_errors().total(), 0u);
  EXPECT_GT(arm.round_trip().count, 100u);  // the loop ran (user-mode Linux timing is slow)
}

}  // namespace
}  // namespace vesica::device
