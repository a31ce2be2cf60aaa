#include "app/calibrate/tool_session.h"

#include <cstdlib>
#include <ctime>
#include <filesystem>

#include "app/calibrate/calibration_steps.h"
#include "app/calibrate/exit_codes.h"

namespace vesica::app::calibrate {

namespace cal = device::calibration;

// NOLINTBEGIN(concurrency-mt-unsafe): read once, before any thread of the tool starts.
std::string DefaultDataDir() {
  if (const char* d = std::getenv("VESICA_CALIBRATION_DIR"); d && *d) return d;
  if (const char* x = std::getenv("XDG_DATA_HOME"); x && *x) return std::string(x) + "/vesica/calibration";
  const char* home = std::getenv("HOME");
  return std::string(home && *home ? home : ".") + "/.local/share/vesica/calibration";
}
// NOLINTEND(concurrency-mt-unsafe)

std::optional<int> ArmNamed(const std::string& name) {
  if (name == "1" || name == "left") return 1;
  if (name == "2" || name == "right") return 2;
  return std::nullopt;
}

ToolSession::ToolSession(ToolOptions options, ToolUi& ui, const std::atomic<bool>* abort)
    : options_(std::move(options)), ui_(ui), abort_(abort) {
  data_dir_ = options_.data_dir.empty() ? DefaultDataDir() : options_.data_dir;
  if (options_.bus.kind == BusSpec::Kind::kEmulated && options_.bus.emulated_state_dir.empty())
    options_.bus.emulated_state_dir = data_dir_ + "/emulated";
}

std::uint32_t ToolSession::date_s() const {
  return options_.date_s != 0 ? options_.date_s : static_cast<std::uint32_t>(std::time(nullptr));
}

const std::string& ToolSession::session_dir() {
  if (!session_dir_.empty()) return session_dir_;
  // One folder per run, named by its UTC start and command; a second run in the same second
  // gets a suffix rather than sharing the first one's files.
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%dT%H%M%SZ", &tm);
  const std::string base = data_dir_ + "/sessions/" + stamp + "-" + options_.command;
  std::string dir = base;
  for (int k = 2; std::filesystem::exists(dir); ++k) dir = base + "-" + std::to_string(k);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  session_dir_ = dir;
  return session_dir_;
}

cal::CalibrationLink* ToolSession::LinkTo(int node, std::string* error) {
  if (auto it = links_.find(node); it != links_.end()) return it->second.get();
  if (!bus_open_) {
    const std::string log = options_.log_path.empty() ? session_dir() + "/bus.log" : options_.log_path;
    if (!bus_.Open(options_.bus, log, error)) return nullptr;
    bus_open_ = true;
  }
  BusObserver* t = bus_.TransportTo(node, error);
  if (!t) return nullptr;
  cal::CalibrationLinkConfig config;
  config.node_id = static_cast<std::uint8_t>(node);
  // Nothing moves outside calibrate and verify: a late joint state there (a loaded host, user-mode
  // Linux) is not a lost arm. In a calibration on a real bus (UDP, CAN) the tool waits as long,
  // twice the node's session watchdog (which zeroes the currents whatever the tool decides): the
  // host's silences measured under load reach 140 ms (docs/protocol.md section 11). On the
  // emulated bus time does not stall: the core's 50 ms stands.
  if ((options_.command != "calibrate" && options_.command != "verify") ||
      options_.bus.kind != BusSpec::Kind::kEmulated)
    config.loss_timeout = std::chrono::milliseconds(500);
  cal::CalibrationLink*& ptr = link_ptrs_[node];
  auto waiter = bus_.WaiterFor(node, ptr, abort_);
  auto link = std::make_unique<cal::CalibrationLink>(
      *t,
      [this, waiter](fp::Nanoseconds until) {
        waiter(until);
        Tick();
      },
      config);
  ptr = link.get();
  links_[node] = std::move(link);
  return ptr;
}

void ToolSession::Progress(int arm, const std::string& step, double fraction) {
  const auto now = std::chrono::steady_clock::now();
  if (step != progress_step_ || arm != progress_arm_) {
    progress_arm_ = arm;
    progress_step_ = step;
    step_wall_start_ = now;
    progress_link_ = link_ptrs_.count(arm) ? link_ptrs_[arm] : nullptr;
    step_bus_start_ = progress_link_ ? progress_link_->now_s() : 0.0;
  }
  progress_fraction_ = fraction;
  const double elapsed = std::chrono::duration<double>(now - step_wall_start_).count();
  const double eta = fraction >= 1.0 ? 0.0 : fraction > 0.02 ? elapsed * (1.0 - fraction) / fraction : -1.0;
  last_shown_ = now;
  ui_.Progress(arm, step, fraction, eta);
}

void ToolSession::Tick() {
  if (progress_step_.empty() || progress_fraction_ >= 1.0 || !progress_link_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_shown_ < std::chrono::milliseconds(200)) return;
  // Steps that report only their start and end: the fraction from the bus time they usually take.
  const std::optional<Step> s = StepNamed(progress_step_);
  const double typical = s ? InfoOf(*s).typical_s : progress_step_ == "homing" ? 8.0 : 1.0;
  const double by_time = std::min(0.95, (progress_link_->now_s() - step_bus_start_) / typical);
  const double f = std::max(progress_fraction_, by_time);
  const double elapsed = std::chrono::duration<double>(now - step_wall_start_).count();
  last_shown_ = now;
  ui_.Progress(progress_arm_, progress_step_, f, f > 0.02 ? elapsed * (1.0 - f) / f : -1.0);
}

CommandOutcome ToolSession::Failure(int code, const std::string& message, nlohmann::json json) {
  CommandOutcome o;
  o.exit_code = code;
  o.json = std::move(json);
  o.json["ok"] = false;
  o.json["error"] = {{"code", code}, {"name", ExitName(code)}, {"message", message}};
  o.text = "error: " + message + "\n";
  return o;
}

}  // namespace vesica::app::calibrate
