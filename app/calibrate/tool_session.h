// One run of a vesica-calibrate command: its options, its bus (opened on first use, with the bus
// log), the per-session folder its files go to, the person's side (ToolUi) and the abort flag
// (Ctrl-C, a panel's button). The commands (commands.h) take one.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "app/calibrate/tool_bus.h"
#include "app/calibrate/tool_ui.h"
#include "device/calibration/calibration_link.h"

namespace vesica::app::calibrate {

inline constexpr const char* kToolVersionText = "0.1.0";
inline constexpr std::uint32_t kToolVersion = 0x000100;  ///< major << 16 | minor << 8 | patch

struct ToolOptions {
  BusSpec bus;
  std::string data_dir;  ///< empty: DefaultDataDir()
  std::string log_path;  ///< empty: bus.log in the session folder
  std::string command = "scan";
  std::uint32_t date_s = 0;  ///< 0: now (recorded in the stored slot)
};

/// $VESICA_CALIBRATION_DIR, else $XDG_DATA_HOME/vesica/calibration, else
/// ~/.local/share/vesica/calibration.
std::string DefaultDataDir();

/// "1", "2", "left" (1), "right" (2): the node id, or nullopt for an unknown arm.
std::optional<int> ArmNamed(const std::string& name);

/// What a command hands back: the exit code, its JSON document and its human text.
struct CommandOutcome {
  int exit_code = 0;
  nlohmann::json json = nlohmann::json::object();
  std::string text;
};

class ToolSession {
 public:
  ToolSession(ToolOptions options, ToolUi& ui, const std::atomic<bool>* abort);

  /// The link to arm `node` (opens the bus and the log on first use); null with *error set.
  device::calibration::CalibrationLink* LinkTo(int node, std::string* error);
  BusObserver* ObserverOf(int node) { return bus_.TransportTo(node, &scratch_); }
  /// The session folder (created on first call).
  const std::string& session_dir();
  std::string data_dir() const { return data_dir_; }
  /// Folder of every image this tool has stored or seen stored (restore --slot looks there).
  std::string image_archive() const { return data_dir_ + "/images"; }
  ToolUi& ui() { return ui_; }
  const ToolOptions& options() const { return options_; }
  ToolBus& bus() { return bus_; }
  bool bus_open() const { return bus_open_; }
  std::string where(int node) const { return bus_.where(node); }
  std::uint32_t date_s() const;
  bool aborted() const { return abort_ && abort_->load(); }

  /// Progress of `arm`'s current step: the core's fraction, a time-based estimate where the core
  /// reports only the start and end, and the time left.
  void Progress(int arm, const std::string& step, double fraction);
  void Tick();

  /// The outcome of a failure: code, message in both forms.
  static CommandOutcome Failure(int code, const std::string& message, nlohmann::json json = nlohmann::json::object());

 private:
  ToolOptions options_;
  ToolUi& ui_;
  const std::atomic<bool>* abort_;
  std::string data_dir_;
  std::string session_dir_;
  ToolBus bus_;
  bool bus_open_ = false;
  std::string scratch_;
  std::map<int, std::unique_ptr<device::calibration::CalibrationLink>> links_;
  std::map<int, device::calibration::CalibrationLink*> link_ptrs_;
  // Progress of the step under way.
  int progress_arm_ = 0;
  std::string progress_step_;
  double progress_fraction_ = 0.0;
  double step_bus_start_ = 0.0;
  std::chrono::steady_clock::time_point step_wall_start_{}, last_shown_{};
  device::calibration::CalibrationLink* progress_link_ = nullptr;
};

}  // namespace vesica::app::calibrate
