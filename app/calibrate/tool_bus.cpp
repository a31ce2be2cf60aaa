#include "app/calibrate/tool_bus.h"

#include <filesystem>
#include <iterator>

#include "firmware_protocol/emulator/arm_emulator.h"
#include "firmware_protocol/emulator/arm_ground_truth.h"
#include "firmware_protocol/transport/socketcan_transport.h"
#include "firmware_protocol/transport/udp_transport.h"
#include "firmware_protocol/transport/virtual_bus.h"

namespace vesica::app::calibrate {

using namespace std::chrono_literals;
namespace emu = fp::emulator;

std::string Describe(const BusSpec& spec) {
  switch (spec.kind) {
    case BusSpec::Kind::kCan:
      return "SocketCAN " + spec.can_interface;
    case BusSpec::Kind::kUdp:
      return "UDP " + spec.udp_host + ":" + std::to_string(spec.udp_base_port);
    case BusSpec::Kind::kEmulated:
      return "emulated arms (seed " + std::to_string(spec.emulated_seed) + ")";
  }
  return "?";
}

ToolBus::~ToolBus() {
  Flush();
  SaveEmulatedFlash();
}

std::string ToolBus::FlashFile(int node) const {
  return spec_.emulated_state_dir + "/seed-" + std::to_string(spec_.emulated_seed) + "-arm-" + std::to_string(node) +
         ".flash";
}

void ToolBus::SaveEmulatedFlash() {
  if (spec_.emulated_state_dir.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(spec_.emulated_state_dir, ec);
  for (auto& [node, arm] : arms_) {
    const auto& bytes = arm->board().flash().bytes();
    std::ofstream out(FlashFile(node), std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  }
}

bool ToolBus::Open(const BusSpec& spec, const std::string& log_path, std::string* error) {
  spec_ = spec;
  log_path_ = log_path;
  std::error_code ec;
  const std::filesystem::path parent = std::filesystem::path(log_path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  log_file_.open(log_path, std::ios::out | std::ios::trunc);
  if (!log_file_) {
    *error = "cannot write the bus log " + log_path;
    return false;
  }
  writer_ = std::make_unique<fp::BusLogWriter>(log_file_);
  if (spec.kind == BusSpec::Kind::kEmulated) {
    clock_ = std::make_unique<fp::VirtualClock>();
    vbus_ = std::make_unique<fp::VirtualBus>(*clock_);
    // Arms 1 and 2 as the trainer has them, each a seeded random arm parked where the rig of the
    // core's tests parks it (the board assumes the design centre; the arm is elsewhere).
    for (int node = 1; node <= 2; ++node) {
      const emu::ArmGroundTruth truth = emu::RandomArm(spec.emulated_seed + static_cast<std::uint64_t>(node - 1));
      emu::ArmEmulator::Config ec2;
      ec2.node_id = static_cast<std::uint8_t>(node);
      ec2.serial = 0x5E51CA00u + static_cast<std::uint32_t>(node);
      ec2.board.park_position = {0.0f, 0.0f, 0.135f};
      auto arm = std::make_unique<emu::ArmEmulator>(vbus_->attach("arm " + std::to_string(node)), truth.plant,
                                                    truth.power_up, ec2);
      emu::HandTarget let_go;
      let_go.holding = false;  // nobody holds the instrument during a calibration
      arm->plant().SetHandScript(emu::HandScript(let_go));
      // The flash the previous run left: the node boots what was stored then.
      if (!spec.emulated_state_dir.empty()) {
        std::ifstream in(FlashFile(node), std::ios::binary);
        std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        auto& flash = arm->board().flash().bytes();
        if (in && bytes.size() == flash.size()) {
          flash = bytes;
          arm->Reboot();
        }
      }
      arms_[node] = std::move(arm);
    }
    // The boot's own Identity (nothing negotiated yet) is on the bus for a moment: a Hello sent
    // meanwhile would take it for the answer and call the node too old. Let the arms boot first.
    AdvanceEmulated(std::chrono::milliseconds(20));
  }
  return true;
}

void ToolBus::Flush() {
  if (writer_) writer_->flush();
}

emu::ArmEmulator* ToolBus::emulated_arm(int node) {
  const auto it = arms_.find(node);
  return it == arms_.end() ? nullptr : it->second.get();
}

std::string ToolBus::where(int node) const {
  switch (spec_.kind) {
    case BusSpec::Kind::kCan:
      return "node " + std::to_string(node) + " on SocketCAN " + spec_.can_interface;
    case BusSpec::Kind::kUdp:
      return "node " + std::to_string(node) + " on UDP " + spec_.udp_host + ":" +
             std::to_string(spec_.udp_base_port + 2 * (node - 1)) + " (vesica-armsim --node-id " +
             std::to_string(node) + ")";
    case BusSpec::Kind::kEmulated:
      return "emulated node " + std::to_string(node);
  }
  return "?";
}

BusObserver* ToolBus::TransportTo(int node, std::string* error) {
  if (auto it = links_.find(node); it != links_.end()) return it->second.observer.get();
  Link link;
  std::string why;
  std::string interface;
  switch (spec_.kind) {
    case BusSpec::Kind::kCan: {
      if (!shared_can_) {
        fp::SocketCanConfig config;
        config.interface = spec_.can_interface;
        shared_can_ = fp::SocketCanTransport::open(config, why);
        if (!shared_can_) {
          *error = "cannot open SocketCAN " + spec_.can_interface + ": " + why;
          return nullptr;
        }
      }
      // One interface carries every node: one logging transport for all of them.
      if (!links_.empty()) {
        Link& first = links_.begin()->second;
        link.raw = first.observer.get();
        link.observer = std::make_unique<BusObserver>(*link.raw);
        BusObserver* o = link.observer.get();
        links_[node] = std::move(link);
        return o;
      }
      link.raw = shared_can_.get();
      interface = spec_.can_interface;
      break;
    }
    case BusSpec::Kind::kUdp: {
      fp::UdpTransportConfig config;
      config.remote_address = spec_.udp_host;
      config.remote_port = static_cast<std::uint16_t>(spec_.udp_base_port + 2 * (node - 1));
      config.local_port = static_cast<std::uint16_t>(config.remote_port + 1);
      auto udp = fp::UdpTransport::open(config, why);
      if (!udp) {
        *error = "cannot open UDP port " + std::to_string(config.local_port) + " for " + where(node) + ": " + why;
        return nullptr;
      }
      link.inner = std::move(udp);
      link.raw = link.inner.get();
      interface = "udp" + std::to_string(node);
      break;
    }
    case BusSpec::Kind::kEmulated:
      link.raw = &vbus_->attach("calibration tool " + std::to_string(node));
      interface = "vcan" + std::to_string(node);
      break;
  }
  link.logging = std::make_unique<fp::LoggingTransport>(*link.raw, *writer_, interface);
  link.observer = std::make_unique<BusObserver>(*link.logging);
  BusObserver* o = link.observer.get();
  links_[node] = std::move(link);
  return o;
}

void ToolBus::AdvanceEmulated(fp::Nanoseconds t) {
  while (clock_->now() < t) {
    vbus_->advance(100us);
    for (auto& [node, arm] : arms_) arm->RunUntil(clock_->now());
  }
}

device::calibration::CalibrationLink::Waiter ToolBus::WaiterFor(int node, device::calibration::CalibrationLink*& link,
                                                                const std::atomic<bool>* abort) {
  fp::Transport* t = links_.at(node).observer.get();
  return [this, t, &link, abort](fp::Nanoseconds until) {
    if (abort && abort->load() && link) link->RequestAbort();
    if (spec_.kind == BusSpec::Kind::kEmulated) {
      AdvanceEmulated(until);
      return;
    }
    while (t->now() < until) {
      t->wait(until - t->now());
      if (abort && abort->load() && link) link->RequestAbort();
    }
  };
}

}  // namespace vesica::app::calibrate
