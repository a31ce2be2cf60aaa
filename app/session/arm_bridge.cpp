#include "app/session/arm_bridge.h"

#include <stdexcept>

#include "firmware_protocol/transport/socketcan_transport.h"
#include "firmware_protocol/transport/udp_transport.h"

namespace vesica::app {

namespace {
bool IsArm(InputKind k) { return k == InputKind::kCanArm || k == InputKind::kEmulatedArm; }

std::unique_ptr<fp::Transport> OpenTransport(const InstrumentConfig& c) {
  std::string error;
  std::unique_ptr<fp::Transport> t;
  if (c.input == InputKind::kCanArm) {
    fp::SocketCanConfig config;
    config.interface = c.can_interface;
    t = fp::SocketCanTransport::open(config, error);
  } else {
    fp::UdpTransportConfig config;
    config.remote_port = static_cast<std::uint16_t>(20000 + 2 * (c.can_node_id - 1));
    config.local_port = static_cast<std::uint16_t>(config.remote_port + 1);
    t = fp::UdpTransport::open(config, error);
  }
  if (!t)
    throw std::runtime_error("instrument '" + c.name + "': cannot open its arm's transport (" +
                             (c.input == InputKind::kCanArm
                                  ? "SocketCAN " + c.can_interface
                                  : "UDP port " + std::to_string(20001 + 2 * (c.can_node_id - 1))) +
                             "): " + error);
  return t;
}
}  // namespace

bool ArmBridge::ScenarioUsesArms(const Scenario& scenario) {
  for (const InstrumentConfig& c : scenario.instruments)
    if (IsArm(c.input)) return true;
  return false;
}

ArmBridge::ArmBridge(const Scenario& scenario) {
  for (const InstrumentConfig& c : scenario.instruments) {
    if (!IsArm(c.input)) continue;
    const size_t slot = c.kind == InstrumentKind::kGrasper ? 0 : 1;
    if (arms_[slot]) continue;  // one arm per hand
    transports_[slot] = OpenTransport(c);
    device::CanArmConfig config;
    config.node_id = static_cast<std::uint8_t>(c.can_node_id);
    // The trainer's haptic thread has no real-time priority: give the node's watchdog slack.
    config.node_watchdog_timeout = std::chrono::milliseconds(50);
    arms_[slot] = std::make_unique<device::CanArm>(*transports_[slot], config);
    arms_[slot]->Open();
    names_[slot] = c.name;
  }
}

ArmBridge::~ArmBridge() {
  for (auto& a : arms_)
    if (a) a->Close();
}

std::array<device::HapticDevice*, 2> ArmBridge::devices() { return {arms_[0].get(), arms_[1].get()}; }

void ArmBridge::Tick() {
  for (auto& a : arms_)
    if (a) a->Tick();
}

std::string ArmBridge::Describe() const {
  std::string out;
  for (size_t i = 0; i < 2; ++i) {
    if (!arms_[i]) continue;
    if (!out.empty()) out += "\n";
    out += "arm      " + names_[i] + ": " + std::string(device::ToString(arms_[i]->Status())) + ", " +
           std::to_string(arms_[i]->link_loss_count()) + " link losses";
  }
  return out;
}

}  // namespace vesica::app
