#include "app/session/arm_bridge.h"

#include <stdexcept>

#include "firmware_protocol/transport/socketcan_transport.h"
#include "firmware_protocol/transport/udp_transport.h"

namespace vesica::app {

namespace {
bool IsArm(InputKind k) { return k == InputKind::kCanArm || k == InputKind::kEmulatedArm; }

size_t SlotOf(const InstrumentConfig& c) { return c.kind == InstrumentKind::kGrasper ? 0 : 1; }

const char* SideOf(size_t slot) { return slot == 0 ? "left arm" : "right arm"; }

std::uint16_t ArmsimPort(const ArmBridgeOptions& o, int node_id) {
  return static_cast<std::uint16_t>(o.udp_base_port + 2 * (node_id - 1));
}

/// Where the arm's node is, in the words of the error and status messages.
std::string LinkOf(const InstrumentConfig& c, const ArmBridgeOptions& o) {
  if (c.input == InputKind::kCanArm)
    return "node " + std::to_string(c.can_node_id) + " on SocketCAN " + c.can_interface;
  return "node " + std::to_string(c.can_node_id) + " on UDP 127.0.0.1:" + std::to_string(ArmsimPort(o, c.can_node_id)) +
         " (vesica-armsim --node-id " + std::to_string(c.can_node_id) + ")";
}

// What the technician runs for this arm when it has no valid calibration: the same bus as ours.
std::string CalibrateCommandOf(const InstrumentConfig& c, const ArmBridgeOptions& o) {
  std::string bus;
  if (c.input == InputKind::kCanArm)
    bus = " --can " + c.can_interface;
  else if (o.udp_base_port != ArmBridgeOptions{}.udp_base_port)
    bus = " --udp-base-port " + std::to_string(o.udp_base_port);
  return "vesica-calibrate" + bus + " calibrate " + std::to_string(c.can_node_id);
}

// What the technician runs for this arm when the bridge could not home it.
std::string HomeCommandOf(const InstrumentConfig& c, const ArmBridgeOptions& o) {
  std::string command = CalibrateCommandOf(c, o);
  return command.replace(command.rfind(" calibrate "), 11, " home ");
}

std::unique_ptr<fp::Transport> OpenTransport(const InstrumentConfig& c, const ArmBridgeOptions& o) {
  std::string error;
  std::unique_ptr<fp::Transport> t;
  if (c.input == InputKind::kCanArm) {
    fp::SocketCanConfig config;
    config.interface = c.can_interface;
    t = fp::SocketCanTransport::open(config, error);
  } else {
    fp::UdpTransportConfig config;
    config.remote_port = ArmsimPort(o, c.can_node_id);
    config.local_port = static_cast<std::uint16_t>(config.remote_port + 1);
    t = fp::UdpTransport::open(config, error);
  }
  if (!t) {
    const std::string where = c.input == InputKind::kCanArm
                                  ? "SocketCAN " + c.can_interface
                                  : "UDP port " + std::to_string(ArmsimPort(o, c.can_node_id) + 1);
    throw std::runtime_error("instrument '" + c.name + "': cannot open its arm's link (" + where + "): " + error);
  }
  return t;
}

/// The arm instruments the bridge drives: the scenario's own, or, when it names none, the
/// emulated arms for its grasper (node 1) and hook (node 2).
std::vector<InstrumentConfig> ArmInstruments(const Scenario& scenario) {
  std::vector<InstrumentConfig> arms;
  for (const InstrumentConfig& c : scenario.instruments)
    if (IsArm(c.input)) arms.push_back(c);
  if (!arms.empty()) return arms;
  for (InstrumentConfig c : scenario.instruments) {
    c.input = InputKind::kEmulatedArm;
    c.can_interface = "virtual";
    c.can_node_id = static_cast<int>(SlotOf(c)) + 1;
    arms.push_back(c);
  }
  return arms;
}
}  // namespace

bool ArmBridge::ScenarioUsesArms(const Scenario& scenario) {
  for (const InstrumentConfig& c : scenario.instruments)
    if (IsArm(c.input)) return true;
  return false;
}

ArmBridge::ArmBridge(const Scenario& scenario, const ArmBridgeOptions& options) {
  if (options.udp_base_port < 1 || options.udp_base_port + 2 * 126 + 1 > 65535)
    throw std::invalid_argument("arm bridge: udp_base_port must leave room for nodes 1..127 below 65536, got " +
                                std::to_string(options.udp_base_port));
  if (options.loss_timeout.count() <= 0) throw std::invalid_argument("arm bridge: loss_timeout must be > 0");
  if (options.node_watchdog.count() < 500 || options.node_watchdog.count() > 100000)
    throw std::invalid_argument("arm bridge: node_watchdog must be 500 .. 100000 us (the node's range), got " +
                                std::to_string(options.node_watchdog.count()) + " us");
  for (const InstrumentConfig& c : ArmInstruments(scenario)) {
    const size_t slot = SlotOf(c);
    if (arms_[slot]) continue;  // one arm per hand: the dissection drives the first of each kind
    if (c.can_node_id < 1 || c.can_node_id > 127)
      throw std::runtime_error("instrument '" + c.name + "': can_node_id must be 1..127, got " +
                               std::to_string(c.can_node_id));
    transports_[slot] = OpenTransport(c, options);
    device::CanArmConfig config;
    config.node_id = static_cast<std::uint8_t>(c.can_node_id);
    config.loss_timeout = options.loss_timeout;
    config.node_watchdog_timeout = options.node_watchdog;
    arms_[slot] = std::make_unique<device::CanArm>(*transports_[slot], config);
    if (const device::DeviceStatus s = arms_[slot]->Open(); s != device::DeviceStatus::kConnecting)
      throw std::runtime_error("instrument '" + c.name + "': its arm (" + LinkOf(c, options) + ") refused to open: " +
                               std::string(device::ToString(s)) + ": " + arms_[slot]->last_error());
    device::ArmSupervisorConfig sc;
    sc.name = SideOf(slot);
    sc.link = LinkOf(c, options);
    sc.calibrate_command = CalibrateCommandOf(c, options);
    sc.home_command = HomeCommandOf(c, options);
    supervisors_[slot] = std::make_unique<device::ArmSupervisor>(*arms_[slot], sc);
    names_[slot] = c.name;
  }
}

ArmBridge::~ArmBridge() {
  for (auto& a : arms_)
    if (a) a->Close();
}

std::array<device::HapticDevice*, 2> ArmBridge::devices() { return {arms_[0].get(), arms_[1].get()}; }

void ArmBridge::Tick() {
  for (size_t i = 0; i < 2; ++i) {
    if (!arms_[i]) continue;
    arms_[i]->Tick();
    supervisors_[i]->Tick(transports_[i]->now());
  }
}

void ArmBridge::ResetFaults() {
  for (auto& s : supervisors_)
    if (s) s->RequestFaultReset();
}

std::vector<device::ArmReport> ArmBridge::Reports() const {
  std::vector<device::ArmReport> out;
  for (const auto& s : supervisors_)
    if (s) out.push_back(s->Report());
  return out;
}

std::string ArmBridge::StatusLines() const {
  std::string out;
  for (const device::ArmReport& r : Reports()) out += (out.empty() ? "" : "\n") + r.text;
  return out;
}

bool ArmBridge::AllOk() const {
  for (const device::ArmReport& r : Reports())
    if (r.status != device::DeviceStatus::kOk) return false;
  return true;
}

std::string ArmBridge::Describe() const {
  std::string out;
  for (size_t i = 0; i < 2; ++i) {
    if (!supervisors_[i]) continue;
    const device::ArmReport r = supervisors_[i]->Report();
    if (!out.empty()) out += "\n";
    out += r.text + " (" + names_[i] + "), " + std::to_string(r.link_losses) + " link losses, " +
           std::to_string(r.automatic_fault_resets) + " watchdog faults cleared";
  }
  return out;
}

}  // namespace vesica::app
