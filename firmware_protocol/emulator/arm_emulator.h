#pragma once

#include <chrono>
#include <cstdint>
#include <memory>

#include "firmware_protocol/emulator/arm_plant.h"
#include "firmware_protocol/emulator/emulated_board.h"
#include "firmware_protocol/node/node.h"
#include "firmware_protocol/transport/transport.h"

namespace vesica::fp::emulator {

/// One emulated arm on a transport: the plant, its board, and the reference firmware node,
/// stepped together on the transport's clock. Works the same on the virtual bus (tests drive
/// the clock) and on CAN over UDP in its own process (vesica-armsim drives it in real time).
class ArmEmulator {
 public:
  struct Config {
    std::uint32_t serial = 0x5E51CA01;
    /// Node id written to a blank emulated flash before the first boot (the node reads its id
    /// from stored parameters); 1..127.
    std::uint8_t node_id = 1;
    Nanoseconds tick_period{std::chrono::microseconds(100)};  ///< node + plant step, 10 kHz
    Nanoseconds send_deadline{std::chrono::milliseconds(1)};  ///< per frame handed to the bus
    EmulatedBoard::Config board;
    /// Firmware of this protocol minor (Node::emulate_firmware_minor): below 3 its factory slot
    /// and its saves are image layout 1, as that firmware's were.
    std::uint8_t firmware_minor = kProtocolMinor;
    /// The node starts every boot not homed (Node::require_homing): a board whose incremental
    /// encoders lose their position while off. Off by default: the emulated arms power up where
    /// they were calibrated, as if their counters were battery-backed.
    bool require_homing = false;
  };

  /// q0: true joint positions at power-up. The flash is programmed as the factory leaves it
  /// (ProgramFactoryFlash: calibrated when params.factory_calibrated), then the node boots at the
  /// transport's current time.
  ArmEmulator(Transport& transport, const ArmPlantParameters& params, const Joint4& q0, const Config& config);

  /// Steps plant and node up to time t of the transport's clock, handing the node every frame
  /// that arrived, and sends what the node queued. Late calls catch up tick by tick.
  void RunUntil(Nanoseconds t);
  /// Power cycle: the node boots again (parameters reloaded from the emulated flash).
  void Reboot();
  /// Power cycle with the arm moved while off to q (true joint positions): the encoders count
  /// from there, so the stored offsets are off by the move until the arm is homed.
  void PowerCycleAt(const Joint4& q);

  ArmPlant& plant() { return *plant_; }
  EmulatedBoard& board() { return *board_; }
  const Node<EmulatedBoard>& node() const { return *node_; }
  Node<EmulatedBoard>& node() { return *node_; }
  std::uint64_t frames_sent() const { return frames_sent_; }
  std::uint64_t frames_not_sent() const { return frames_not_sent_; }

 private:
  void Flush(Nanoseconds now);

  Transport& transport_;
  Config config_;
  std::unique_ptr<ArmPlant> plant_;
  std::unique_ptr<EmulatedBoard> board_;
  std::unique_ptr<Node<EmulatedBoard>> node_;
  Nanoseconds origin_;  ///< transport time of power-up; plant time counts from here
  Nanoseconds next_tick_;
  std::uint64_t frames_sent_ = 0;
  std::uint64_t frames_not_sent_ = 0;
};

}  // namespace vesica::fp::emulator
