// The calibration tool's bus to the arms, as the trainer has them: SocketCAN (one interface, every
// node on it), CAN over UDP to vesica-armsim (arm n on base + 2(n-1), the tool on the port above,
// as app/session/arm_bridge.h), or emulated arms on an in-process virtual bus (seeded random arms,
// bus time instead of wall time: training and tests). Every frame goes to the session's bus log
// in candump -l format.
#pragma once

#include <atomic>
#include <cstdint>
#include <fstream>
#include <map>
#include <memory>
#include <string>

#include "app/calibrate/bus_observer.h"
#include "device/calibration/calibration_link.h"
#include "firmware_protocol/buslog/bus_log_writer.h"
#include "firmware_protocol/buslog/logging_transport.h"
#include "firmware_protocol/emulator/arm_emulator.h"
#include "firmware_protocol/transport/virtual_bus.h"
#include "firmware_protocol/transport/virtual_clock.h"

namespace vesica::app::calibrate {

struct BusSpec {
  enum class Kind { kUdp, kCan, kEmulated };
  Kind kind = Kind::kUdp;
  std::string can_interface = "can0";
  std::string udp_host = "127.0.0.1";
  int udp_base_port = 20000;
  std::uint64_t emulated_seed = 1;  ///< arm n is RandomArm(seed + n - 1)
  /// Emulated arms keep their flash here between runs (seed-S-arm-N.flash), so calibrate,
  /// verify and restore see what the previous run stored; empty: blank flash, nothing kept.
  std::string emulated_state_dir;
};

/// "udp 127.0.0.1:20000", "SocketCAN can0", "emulated (seed 7)".
std::string Describe(const BusSpec& spec);

class ToolBus {
 public:
  /// Opens nothing yet but the log file (its folder is created); false with a message if it cannot.
  bool Open(const BusSpec& spec, const std::string& log_path, std::string* error);
  ~ToolBus();

  /// The transport to `node` (1..127), opened on first use; null with a message when it cannot open.
  BusObserver* TransportTo(int node, std::string* error);
  /// Waits on the bus's clock; sets the link's abort when *abort becomes true (Ctrl-C, a button).
  device::calibration::CalibrationLink::Waiter WaiterFor(int node, device::calibration::CalibrationLink*& link,
                                                         const std::atomic<bool>* abort);
  std::string where(int node) const;
  std::uint64_t frames_logged() const { return writer_ ? writer_->lines_written() : 0; }
  const std::string& log_path() const { return log_path_; }
  void Flush();
  bool emulated() const { return spec_.kind == BusSpec::Kind::kEmulated; }
  /// Emulated bus only: the arm behind node n (null otherwise).
  fp::emulator::ArmEmulator* emulated_arm(int node);

 private:
  struct Link {
    std::unique_ptr<fp::Transport> inner;  // null where shared (CAN) or an endpoint (emulated)
    fp::Transport* raw = nullptr;
    std::unique_ptr<fp::LoggingTransport> logging;
    std::unique_ptr<BusObserver> observer;
  };
  void AdvanceEmulated(fp::Nanoseconds t);
  std::string FlashFile(int node) const;
  void SaveEmulatedFlash();

  BusSpec spec_;
  std::string log_path_;
  std::ofstream log_file_;
  std::unique_ptr<fp::BusLogWriter> writer_;
  std::unique_ptr<fp::Transport> shared_can_;
  std::map<int, Link> links_;
  // Emulated: the clock, the bus and one arm per node.
  std::unique_ptr<fp::VirtualClock> clock_;
  std::unique_ptr<fp::VirtualBus> vbus_;
  std::map<int, std::unique_ptr<fp::emulator::ArmEmulator>> arms_;
};

}  // namespace vesica::app::calibrate
