#include "firmware_protocol/emulator/arm_emulator.h"

#include "firmware_protocol/emulator/factory_calibration.h"

namespace vesica::fp::emulator {
namespace {

std::uint64_t Micros(Nanoseconds t) { return static_cast<std::uint64_t>(t.count() / 1000); }

}  // namespace

ArmEmulator::ArmEmulator(Transport& transport, const ArmPlantParameters& params, const Joint4& q0,
                         const Config& config)
    : transport_(transport),
      config_(config),
      plant_(std::make_unique<ArmPlant>(params, q0)),
      board_(std::make_unique<EmulatedBoard>(*plant_, config.board)),
      node_(std::make_unique<Node<EmulatedBoard>>(*board_, config.serial)),
      origin_(transport.now()),
      next_tick_(origin_) {
  node_->emulate_firmware_minor(config.firmware_minor);
  node_->require_homing(config.require_homing);
  ProgramFactoryFlash(*board_, params, q0, config.board.park_position, config.node_id, config.serial,
                      config.firmware_minor < kLayout2Minor ? 1 : ParameterStore::kLayoutVersion);
  node_->boot(Micros(next_tick_));
  Flush(next_tick_);
}

void ArmEmulator::Reboot() {
  node_->boot(Micros(next_tick_));
  Flush(next_tick_);
}

void ArmEmulator::PowerCycleAt(const Joint4& q) {
  plant_->PowerUpAt(q);
  board_->PowerUp();
  Reboot();
}

void ArmEmulator::Flush(Nanoseconds now) {
  // While catching up after a stall, tick time lags the transport's clock: the deadline counts
  // from whichever is later, or every catch-up frame would be dropped as already late.
  const Nanoseconds wall = transport_.now();
  const Nanoseconds deadline = (wall > now ? wall : now) + config_.send_deadline;
  CanFrame f;
  while (node_->pop_tx(f)) {
    if (transport_.send(f, deadline) == SendStatus::Queued) {
      ++frames_sent_;
    } else {
      ++frames_not_sent_;
    }
  }
}

void ArmEmulator::RunUntil(Nanoseconds t) {
  while (next_tick_ <= t) {
    plant_->Advance(std::chrono::duration<double>(next_tick_ - origin_).count() - plant_->time_s());
    TimedFrame rx;
    while (transport_.receive(rx)) {
      // A frame is handled no earlier than it arrived and never before the previous tick.
      const Nanoseconds at = rx.timestamp > next_tick_ ? next_tick_ : rx.timestamp;
      node_->on_frame(rx.frame, Micros(at));
      Flush(next_tick_);  // replies go out at once, as from the CAN receive interrupt
    }
    node_->tick(Micros(next_tick_));
    Flush(next_tick_);
    next_tick_ += config_.tick_period;
  }
  // Frames that arrived since the last tick are answered now, not at the next tick boundary.
  TimedFrame rx;
  while (transport_.receive(rx)) {
    node_->on_frame(rx.frame, Micros(rx.timestamp < t ? rx.timestamp : t));
    Flush(t);
  }
}

}  // namespace vesica::fp::emulator
