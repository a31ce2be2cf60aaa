// A host bridge and an emulated arm on one virtual bus, stepped together on the bus clock.
#pragma once

#include <chrono>
#include <cmath>
#include <memory>

#include "device/can_arm.h"
#include "firmware_protocol/emulator/arm_emulator.h"
#include "firmware_protocol/transport/virtual_bus.h"

namespace vesica::device::testing {

using namespace std::chrono_literals;
namespace emu = fp::emulator;

inline emu::Vec3 ToVec3(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
inline Eigen::Vector3d ToEigen(const emu::Vec3& v) { return {v[0], v[1], v[2]}; }

struct BridgeRig {
  static constexpr emu::Joint4 kStart{0.2, -0.1, 0.0, 0.12};

  fp::VirtualClock clock;
  fp::VirtualBus bus{clock};
  fp::VirtualBusEndpoint& host_ep = bus.attach("host");
  fp::VirtualBusEndpoint& arm_ep = bus.attach("arm");
  std::unique_ptr<emu::ArmEmulator> emulator;
  std::unique_ptr<CanArm> arm;
  bool host_running = true;
  bool arm_running = true;  ///< false: the arm's process is gone (see KillArm / StartArm)
  int step = 0;

  /// The emulated arm's plant: the nominal arm, factory calibrated (set factory_calibrated = false
  /// for a board nobody calibrated).
  emu::ArmPlantParameters plant = emu::ArmPlantParameters::Nominal();

  explicit BridgeRig(const CanArmConfig& config = {}) : BridgeRig(config, emu::ArmPlantParameters::Nominal()) {}
  BridgeRig(const CanArmConfig& config, const emu::ArmPlantParameters& arm_plant) : plant(arm_plant) {
    StartArm();
    arm = std::make_unique<CanArm>(host_ep, config);
  }

  /// A fresh arm process (vesica-armsim started again): a new node boots now on the flash the
  /// factory left (calibrated, unless plant.factory_calibrated is false: then blank).
  void StartArm() {
    emu::ArmEmulator::Config ec;
    ec.board.park_position = {static_cast<float>(kStart[0]), static_cast<float>(kStart[1]),
                              static_cast<float>(kStart[3])};
    fp::TimedFrame stale;
    while (arm_ep.receive(stale)) {}  // a new process does not read its predecessor's socket
    arm_ep.set_connected(true);
    emulator = std::make_unique<emu::ArmEmulator>(arm_ep, plant, kStart, ec);
    emu::HandTarget hold;
    hold.p_T = emu::TipPosition(kStart);
    emulator->plant().SetHandScript(emu::HandScript(hold));
    arm_running = true;
  }
  /// The arm's process dies: nothing answers any more.
  void KillArm() {
    arm_running = false;
    arm_ep.set_connected(false);
  }

  /// Advances bus time by `seconds` in 100 us steps; the host ticks every 1 ms while running.
  /// `each_ms` runs after every host period (1 ms of bus time).
  template <class F>
  void Run(double seconds, F&& each_ms) {
    const int steps = static_cast<int>(std::lround(seconds / 1e-4));
    for (int i = 0; i < steps; ++i) {
      bus.advance(100us);
      if (arm_running) emulator->RunUntil(clock.now());
      if (++step % 10 == 0) {
        if (host_running) arm->Tick();
        each_ms();
      }
    }
  }
  void Run(double seconds) { Run(seconds, [] {}); }
};

}  // namespace vesica::device::testing
