// One randomised emulated arm and the calibration tool on a virtual bus, stepped together on the
// bus clock: the tool's waiter advances the bus and the arm in 100 us steps.
#pragma once

#include <chrono>
#include <functional>
#include <memory>

#include "device/calibration/calibration_link.h"
#include "firmware_protocol/emulator/arm_emulator.h"
#include "firmware_protocol/emulator/arm_ground_truth.h"
#include "firmware_protocol/transport/virtual_bus.h"

namespace vesica::device::calibration::testing {

using namespace std::chrono_literals;
namespace emu = fp::emulator;

struct CalibrationRig {
  emu::ArmGroundTruth truth;
  fp::VirtualClock clock;
  fp::VirtualBus bus{clock};
  fp::VirtualBusEndpoint& tool_ep = bus.attach("calibration tool");
  fp::VirtualBusEndpoint& arm_ep = bus.attach("arm");
  std::unique_ptr<emu::ArmEmulator> emulator;
  std::unique_ptr<CalibrationLink> link;
  /// Runs every 100 us of bus time (fault injection); null: nothing.
  std::function<void()> each_step;

  explicit CalibrationRig(std::uint64_t seed) : truth(emu::RandomArm(seed)) {
    emu::ArmEmulator::Config ec;
    // The board assumes the arm powered up at the design centre; it did not (truth.power_up).
    ec.board.park_position = {0.0f, 0.0f, 0.135f};
    emulator = std::make_unique<emu::ArmEmulator>(arm_ep, truth.plant, truth.power_up, ec);
    emu::HandTarget let_go;
    let_go.holding = false;  // nobody holds the instrument during a calibration
    emulator->plant().SetHandScript(emu::HandScript(let_go));
    link = std::make_unique<CalibrationLink>(tool_ep, [this](fp::Nanoseconds t) { RunUntil(t); });
  }

  void RunUntil(fp::Nanoseconds t) {
    while (clock.now() < t) {
      bus.advance(100us);
      emulator->RunUntil(clock.now());
      if (each_step) each_step();
    }
  }
  /// The position_offset that makes the node's reading equal the true joint position for joint j:
  /// the board reads park + counts since power-up, and counts are whole (floor), so the reading
  /// is centred on the truth with half a count added.
  double TrueOffset(int j, int direction) const {
    return truth.power_up[emu::JointOfMotor(j)] - direction * ParkPosition(j) + 0.5 * truth.count(j);
  }
  static double ParkPosition(int j) { return j == 2 ? static_cast<double>(0.135f) : 0.0; }
};

}  // namespace vesica::device::calibration::testing
