// vesica-calibrate: the technician's tool for the arms' motor calibration (issue 32), in the
// manner of moteus_tool and odrivetool. docs/calibration.md is its guide.
#include <sched.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <iostream>

#include "app/calibrate/commands.h"
#include "app/calibrate/exit_codes.h"
#include "app/calibrate/terminal_ui.h"

namespace {

std::atomic<bool> g_interrupted{false};

// The first Ctrl-C asks the step to stop (the link aborts the session, the node reloads its
// stored calibration); a second one ends the program at once.
void OnSigint(int) {
  g_interrupted.store(true);
  std::signal(SIGINT, SIG_DFL);
}

int Run(int argc, char** argv) {
  namespace c = vesica::app::calibrate;
  CLI::App app{"vesica-calibrate: find, calibrate, verify and restore the Vesica arms (docs/calibration.md)"};
  app.require_subcommand(1);
  app.fallthrough();
  c::ToolOptions options;
  std::string can_interface;
  bool udp = false;
  std::uint64_t emulated_seed = 0;
  bool json = false, yes = false, quiet = false;
  int realtime_priority = 0;
  app.add_option("--can", can_interface, "SocketCAN interface the arms are on (e.g. can0)");
  app.add_flag("--udp", udp, "CAN over UDP to vesica-armsim (the default)");
  app.add_option("--udp-host", options.bus.udp_host, "vesica-armsim's address (IPv4)");
  app.add_option("--udp-base-port", options.bus.udp_base_port,
                 "arm n listens on this + 2(n-1), the tool on the port above (as the trainer)")
      ->check(CLI::Range(1, 65531));
  app.add_option(
         "--emulated", emulated_seed,
         "in-process emulated random arms (arm n: seed + n - 1, seed >= 1), in bus time: for training and tests")
      ->check(CLI::Validator(
          [](std::string& v) { return v == "0" ? std::string("the seed is 1 or more") : std::string(); }, "SEED >= 1"));
  app.add_flag("--json", json, "print one JSON document (stable keys) on stdout");
  app.add_flag("-y,--yes", yes, "answer yes to the prompt before an arm moves (scripts)");
  app.add_flag("-q,--quiet", quiet, "no progress or notes on stderr");
  app.add_option("--log", options.log_path, "bus log file (candump -l format; default bus.log in the session folder)");
  app.add_option("--dir", options.data_dir,
                 "folder of sessions and stored images (default $VESICA_CALIBRATION_DIR or "
                 "~/.local/share/vesica/calibration)");
  app.add_option("--realtime-priority", realtime_priority,
                 "run the servo at SCHED_FIFO priority N (a host-driven calibration over UDP or CAN on a busy "
                 "host stays accurate; needs CAP_SYS_NICE), 0: normal scheduling")
      ->check(CLI::Range(0, 99));
  app.add_option("--date", options.date_s, "calibration date recorded in the slot, Unix time (default now)");

  std::string arm_name;
  CLI::App* scan = app.add_subcommand("scan", "find the arms: identity, versions, state, faults, calibration slots");
  CLI::App* info = app.add_subcommand("info", "one arm in full, with its stored calibration");
  info->add_option("ARM", arm_name, "1 (left) or 2 (right)")->required();
  CLI::App* calibrate = app.add_subcommand("calibrate", "calibrate an arm's motors and joints (the arm moves)");
  calibrate->add_option("ARM", arm_name, "1 (left) or 2 (right)")->required();
  std::string joint, step;
  calibrate->add_option("--joint", joint, "one joint only: yaw, pitch or insertion");
  calibrate->add_option("--step", step, "this step only (the others keep the stored values): " + c::StepNames());
  CLI::App* verify =
      app.add_subcommand("verify", "measure again and compare with the stored calibration (the arm moves)");
  verify->add_option("ARM", arm_name, "1 (left) or 2 (right)")->required();
  verify->add_option("--joint", joint, "one joint only: yaw, pitch or insertion");
  CLI::App* restore = app.add_subcommand("restore", "put a stored calibration back in force");
  restore->add_option("ARM", arm_name, "1 (left) or 2 (right)")->required();
  std::string slot, file;
  CLI::Option* slot_opt = restore->add_option("--slot", slot, "the node's slot A or B (default: the one not in use)")
                              ->check(CLI::IsMember({"A", "B", "a", "b"}));
  restore->add_option("--file", file, "an image file (beside a report)")->excludes(slot_opt);
  CLI::App* report = app.add_subcommand("report", "a report (JSON + HTML) of the calibration in force");
  report->add_option("ARM", arm_name, "1 (left) or 2 (right)")->required();
  CLI::App* home = app.add_subcommand(
      "home", "find the arm's positions again after power-up: lower hard stop, then index (the arm moves)");
  home->add_option("ARM", arm_name, "1 (left) or 2 (right)")->required();
  home->add_option("--joint", joint, "one joint only: yaw, pitch or insertion");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    if (rc == 0) return c::kExitOk;  // --help
    // A script that asked for JSON gets JSON for a bad command line too.
    for (int i = 1; i < argc; ++i)
      if (std::string(argv[i]) == "--json") {
        nlohmann::json j = c::ToolSession::Failure(c::kExitUsage, e.what()).json;
        j["exit_code"] = static_cast<int>(c::kExitUsage);
        std::cout << j.dump(2) << "\n";
      }
    return c::kExitUsage;
  }

  const auto usage = [&](int code, const std::string& message) {
    if (json) {
      nlohmann::json j = c::ToolSession::Failure(code, message).json;
      j["exit_code"] = code;
      std::cout << j.dump(2) << "\n";
    }
    std::fprintf(stderr, "vesica-calibrate: %s\n", message.c_str());
    return code;
  };
  const int transports = (can_interface.empty() ? 0 : 1) + (udp ? 1 : 0) + (emulated_seed ? 1 : 0);
  if (transports > 1) return usage(c::kExitUsage, "choose one of --can, --udp and --emulated");
  if (!can_interface.empty()) {
    options.bus.kind = c::BusSpec::Kind::kCan;
    options.bus.can_interface = can_interface;
  } else if (emulated_seed) {
    options.bus.kind = c::BusSpec::Kind::kEmulated;
    options.bus.emulated_seed = emulated_seed;
  }
  CLI::App* command = app.get_subcommands().front();
  options.command = command->get_name();
  int arm = 0;
  if (command != scan) {
    const auto named = c::ArmNamed(arm_name);
    // Checked before anything is opened: an unknown arm writes nothing.
    if (!named) return usage(c::kExitNoArm, "unknown arm '" + arm_name + "': the arms are 1 (left) and 2 (right)");
    arm = *named;
  }
  c::CalibrateRequest request;
  if (!joint.empty()) {
    const int j = joint == "yaw" || joint == "0"         ? 0
                  : joint == "pitch" || joint == "1"     ? 1
                  : joint == "insertion" || joint == "2" ? 2
                                                         : -1;
    if (j < 0) return usage(c::kExitUsage, "unknown joint '" + joint + "': yaw, pitch or insertion");
    request.joints = 1u << j;
  }
  if (!step.empty()) {
    const auto s = c::StepNamed(step);
    if (!s) return usage(c::kExitUsage, "unknown step '" + step + "': " + c::StepNames());
    request.steps = {*s};
  }

  if (realtime_priority > 0) {
    sched_param param{};
    param.sched_priority = realtime_priority;
    if (sched_setscheduler(0, SCHED_FIFO, &param) != 0)
      std::fprintf(stderr, "vesica-calibrate: SCHED_FIFO priority %d refused (%s); running with normal scheduling\n",
                   realtime_priority, std::strerror(errno));
  }
  c::TerminalUi ui(yes, quiet);
  std::signal(SIGINT, OnSigint);
  c::ToolSession session(options, ui, &g_interrupted);
  c::CommandOutcome o;
  try {
    if (command == scan)
      o = c::Scan(session);
    else if (command == info)
      o = c::Info(session, arm);
    else if (command == calibrate)
      o = c::Calibrate(session, arm, request);
    else if (command == verify)
      o = c::Verify(session, arm, request);
    else if (command == restore) {
      c::RestoreRequest r;
      r.file = file;
      if (!slot.empty()) r.slot = (slot == "A" || slot == "a") ? 0 : 1;
      o = c::Restore(session, arm, r);
    } else if (command == report) {
      o = c::Report(session, arm);
    } else if (command == home) {
      c::HomeRequest h;
      h.joints = request.joints;
      o = c::Home(session, arm, h);
    }
  } catch (const std::exception& e) {
    o = c::ToolSession::Failure(c::kExitInternal, std::string("internal error: ") + e.what());
  }
  session.bus().Flush();
  if (session.bus_open()) {
    o.json["bus_log"] = session.bus().log_path();
    o.json["bus_log_frames"] = session.bus().frames_logged();
  }
  o.json["exit_code"] = o.exit_code;
  if (json) {
    std::cout << o.json.dump(2) << "\n";
  } else if (o.exit_code == c::kExitOk) {
    std::cout << o.text;
    if (session.bus_open()) std::cout << "bus log: " << session.bus().log_path() << "\n";
  } else {
    std::cerr << "vesica-calibrate: " << o.text;
    if (session.bus_open()) std::cerr << "bus log: " << session.bus().log_path() << "\n";
  }
  return o.exit_code;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vesica-calibrate: internal error: %s\n", e.what());
  } catch (...) {
    std::fprintf(stderr, "vesica-calibrate: internal error\n");
  }
  return vesica::app::calibrate::kExitInternal;
}
