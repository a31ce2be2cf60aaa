// vesica-armsim: one emulated 4-DOF arm (plant + reference firmware node) in its own process,
// talking CAN over UDP (cannelloni packet format) in real time, so the host bridge, candump-style
// tools and real CAN/UDP gateways can connect to it like to an arm on can0.
#include <sched.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "app/armsim/armsim_transport.h"
#include "app/armsim/fixture_control.h"
#include "app/armsim/hand_trajectory.h"
#include "device/input/input_recording.h"
#include "firmware_protocol/emulator/arm_emulator.h"
#include "firmware_protocol/emulator/arm_ground_truth.h"

namespace {

std::atomic<bool> g_stop{false};
void OnSignal(int) { g_stop.store(true); }

// The reference directions' elevations of the shipped cholecystectomy scenarios (trocar to the
// laparoscope's target): the left (grasper) port looks 15.2 degrees down, the right (hook) 9.5 up.
constexpr double kShippedLeftElevationDeg = -15.214833;
constexpr double kShippedRightElevationDeg = 9.533593;

}  // namespace

int main(int argc, char** argv) {
  namespace emu = vesica::fp::emulator;
  CLI::App app{"vesica-armsim: emulated Vesica arm on CAN over UDP (cannelloni format)"};
  vesica::app::ArmsimUdpOptions udp;
  double duration_s = 0.0;
  int tick_us = 100;
  int node_id = 1;
  int realtime_priority = 0;
  double hand_x_mm = 0.0, hand_y_mm = 0.0, depth_mm = 120.0;
  std::string log_level = "info";
  bool report = false;
  std::vector<std::string> hand = {"hold"};
  std::string side;
  double elevation_deg = 1000.0;  // not given: the shipped scenario's, for the side
  double figure8_mm = 25.0, figure8_period_s = 6.0;
  // The trainer's bridge (app/session/arm_bridge.h) expects node n on 20000 + 2(n-1), answering
  // to the next port: the defaults follow --node-id, so `--node-id 2` alone is the right arm.
  CLI::Option* local_port = app.add_option("--local-port", udp.local_port,
                                           "UDP port this arm listens on (default 20000 + 2 (node id - 1))")
                                ->check(CLI::Range(1, 65535));
  app.add_option("--remote-host", udp.remote_host, "host bridge address (IPv4)");
  CLI::Option* remote_port =
      app.add_option("--remote-port", udp.remote_port, "host bridge UDP port (default the local port + 1)")
          ->check(CLI::Range(1, 65535));
  app.add_option("--duration-s", duration_s, "stop after this many seconds (0: until SIGINT/SIGTERM)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--node-id", node_id, "CAN node id of this arm")->check(CLI::Range(1, 127));
  app.add_option("--tick-us", tick_us, "node and plant step, microseconds")->check(CLI::Range(20, 1000));
  app.add_option("--hand-x-mm", hand_x_mm, "hand target, trocar frame x, mm");
  app.add_option("--hand-y-mm", hand_y_mm, "hand target, trocar frame y, mm");
  app.add_option("--depth-mm", depth_mm, "park insertion depth and hand target depth, mm")
      ->check(CLI::Range(20.0, 250.0));
  CLI::Option* hand_option =
      app.add_option(
             "--hand", hand,
             "what the hand does: 'hold' (at --hand-x-mm/--hand-y-mm/--depth-mm), 'figure8' (about that point), "
             "or 'recording FILE' (one instrument of a recorded session, e.g. data/recordings/dissection.csv)")
          ->expected(1, 2);
  app.add_option("--side", side, "recording: which instrument the hand plays, left or right (default: left for node 1, "
                                 "right otherwise)")
      ->check(CLI::IsMember({"left", "right"}));
  app.add_option("--reference-elevation-deg", elevation_deg,
                 "recording: elevation of the instrument's reference direction (trocar to the laparoscope's target) "
                 "above the horizontal, degrees (default: the shipped cholecystectomy scenarios', -15.2 left, 9.5 right)")
      ->check(CLI::Range(-89.0, 89.0));
  app.add_option("--figure8-mm", figure8_mm, "figure8: half-width, mm")->check(CLI::Range(1.0, 100.0));
  app.add_option("--figure8-period-s", figure8_period_s, "figure8: seconds per loop")->check(CLI::Range(0.5, 600.0));
  app.add_option("--realtime-priority", realtime_priority, "SCHED_FIFO priority, 0: normal scheduling")
      ->check(CLI::Range(0, 99));
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error");
  app.add_flag("--report", report, "print the final plant state as one key=value line on stdout");
  std::uint64_t random_arm = 0;
  app.add_option("--random-arm", random_arm,
                 "a seeded random arm (RandomArm: encoder, stops, friction, gravity...) as built, powered up off "
                 "centre and nobody holding it: what vesica-calibrate must find (0: the nominal arm)");
  bool uncalibrated = false;
  app.add_flag("--uncalibrated", uncalibrated,
               "the nominal arm with a blank flash, as a board nobody calibrated: the trainer's bridge refuses to "
               "enable it until vesica-calibrate has calibrated it (default: it left the factory calibrated)");
  bool fixture_control = false;
  app.add_flag("--fixture-control", fixture_control,
               "take what a technician does by hand from standard input, one command a line: 'reference-load "
               "on|off', 'hand roll=RAD jaw=RAD pedal=0..1', 'let-go' (each answered 'ok ...' on standard output), so "
               "that vesica-calibrate's torque-constant check and guided hand steps run over UDP");
  int firmware_minor = vesica::fp::kProtocolMinor;
  app.add_option("--firmware-minor", firmware_minor,
                 "emulate firmware of this protocol minor (1.x): below 3 it stores image layout 1 and has no "
                 "torque-constant correction or hand-sensor calibration")
      ->check(CLI::Range(1, static_cast<int>(vesica::fp::kProtocolMinor)));
  double moved_while_off_rad = 0.0;
  app.add_option("--moved-while-off", moved_while_off_rad,
                 "the arm was moved by hand while off: it powers up this far (rad; insertion a tenth of it in m) from "
                 "where it was calibrated, each way drawn from --moved-seed, and its node requires homing (protocol "
                 "1.4): the bridge or `vesica-calibrate home` homes it before it is enabled")
      ->check(CLI::Range(0.0, 0.9));
  std::uint64_t moved_seed = 1;
  app.add_option("--moved-seed", moved_seed, "the seed of --moved-while-off's directions");
  bool require_homing = false;
  app.add_flag("--require-homing", require_homing,
               "the node starts not homed, as a board whose incremental encoders lose their position while off "
               "(implied by --moved-while-off)");
  CLI11_PARSE(app, argc, argv);
  if (local_port->count() == 0) udp.local_port = 20000 + 2 * (node_id - 1);
  if (remote_port->count() == 0) udp.remote_port = udp.local_port + 1;
  spdlog::set_level(spdlog::level::from_str(log_level));

  // The hand's script is built before the link opens: a bad recording is refused at once.
  const double depth = depth_mm * 1e-3;
  const emu::Vec3 hold_T{hand_x_mm * 1e-3, hand_y_mm * 1e-3, depth};
  emu::HandScript script;
  std::string hand_text;
  try {
    const std::string& mode = hand.at(0);
    if ((mode == "recording") != (hand.size() == 2))
      throw std::invalid_argument("--hand: 'recording' takes a FILE, 'hold' and 'figure8' take nothing");
    if (mode == "hold") {
      script = vesica::app::HoldingHand(hold_T);
      hand_text = "holding";
    } else if (mode == "figure8") {
      script = vesica::app::FigureEightHand(hold_T, figure8_mm * 1e-3, figure8_period_s);
      hand_text = "tracing a figure eight";
    } else if (mode == "recording") {
      const bool left = side.empty() ? node_id == 1 : side == "left";
      if (elevation_deg > 90.0) elevation_deg = left ? kShippedLeftElevationDeg : kShippedRightElevationDeg;
      const vesica::device::InputRecording recording = vesica::device::ReadInputRecording(hand[1]);
      script = vesica::app::RecordedHand(recording, left ? vesica::device::kLeft : vesica::device::kRight,
                                         elevation_deg * std::numbers::pi / 180.0, {0.0, 0.0, depth});
      hand_text = "playing the " + std::string(left ? "left" : "right") + " instrument of " + hand[1] + " (" +
                  std::to_string(recording.frames.size()) + " frames, repeating)";
    } else {
      throw std::invalid_argument("--hand: unknown '" + mode + "' (hold, figure8, recording FILE)");
    }
  } catch (const std::exception& e) {
    spdlog::error("vesica-armsim: {}", e.what());
    return 2;
  }

  std::unique_ptr<vesica::fp::Transport> transport;
  std::string error;
  if (!vesica::app::OpenArmsimUdp(udp, &transport, &error)) {
    spdlog::error("vesica-armsim: {}", error);
    return 2;
  }
  if (realtime_priority > 0) {
    sched_param param{};
    param.sched_priority = realtime_priority;
    if (sched_setscheduler(0, SCHED_FIFO, &param) != 0)
      spdlog::warn("vesica-armsim: SCHED_FIFO priority {} refused ({}), running with normal scheduling",
                   realtime_priority, std::strerror(errno));
  }
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);

  emu::Joint4 q0{0.0, 0.0, 0.0, depth};
  emu::ArmEmulator::Config config;
  config.tick_period = std::chrono::microseconds(tick_us);
  config.node_id = static_cast<std::uint8_t>(node_id);
  config.board.park_position = {0.0f, 0.0f, static_cast<float>(depth)};
  emu::ArmPlantParameters plant = emu::ArmPlantParameters::Nominal();
  plant.factory_calibrated = !uncalibrated;
  if (random_arm != 0) {
    // As the calibration tests' rig: the board assumes the design centre, the arm is elsewhere.
    const emu::ArmGroundTruth truth = emu::RandomArm(random_arm);
    plant = truth.plant;
    q0 = truth.power_up;
    config.board.park_position = {0.0f, 0.0f, static_cast<float>(emu::ArmGroundTruth::kDesignCentre[2])};
    emu::HandTarget let_go;
    let_go.holding = false;
    script = emu::HandScript(let_go);
    hand_text = "of random arm " + std::to_string(random_arm) + " not holding it";
  }
  config.firmware_minor = static_cast<std::uint8_t>(firmware_minor);
  config.require_homing = require_homing || moved_while_off_rad > 0.0;
  emu::ArmEmulator arm(*transport, plant, q0, config);
  if (moved_while_off_rad > 0.0) {
    // Calibrated (the factory's, or a flash of an earlier run) where it was; moved while off.
    const emu::Joint4 moved = emu::MovedWhileOff(plant, q0, moved_while_off_rad, moved_seed);
    arm.PowerCycleAt(moved);
    if (hand_option->count() == 0) {  // nobody holds an arm that is homing (it seeks its stops)
      emu::HandTarget let_go;
      let_go.holding = false;
      script = emu::HandScript(let_go);
      hand_text = "not holding it (it must be homed)";
    }
    spdlog::info(
        "vesica-armsim: powered up moved while off: yaw {:+.4f} rad, pitch {:+.4f} rad, insertion {:+.4f} m "
        "from where it was calibrated",
        moved[0] - q0[0], moved[1] - q0[1], moved[3] - q0[3]);
  }
  arm.plant().SetHandScript(script);
  vesica::app::FixtureControl fixture;
  spdlog::info("vesica-armsim: node {} listening on UDP {} -> {}:{}, the hand {}", arm.node().node_id(),
               udp.local_port, udp.remote_host, udp.remote_port, hand_text);

  const auto start = transport->now();
  auto next_log = start;
  while (!g_stop.load()) {
    const auto now = transport->now();
    if (duration_s > 0 && now - start >= std::chrono::duration<double>(duration_s)) break;
    arm.RunUntil(now);
    if (fixture_control) fixture.Poll(arm.plant());
    if (now >= next_log) {
      next_log = now + std::chrono::seconds(1);
      const auto f = arm.plant().ForceOnHand();
      spdlog::debug("state {} fault {} hand force [{:.3f} {:.3f} {:.3f}] N", vesica::fp::to_string(arm.node().state()),
                    vesica::fp::to_string(arm.node().latched_fault()), f[0], f[1], f[2]);
    }
    transport->wait(config.tick_period);
  }
  if (report) {
    const auto f = arm.plant().ForceOnHand();
    const auto a = arm.plant().ActuatorTipForce();
    std::printf("hand_force_N=%.6f,%.6f,%.6f actuator_force_N=%.6f,%.6f,%.6f state=%s fault=%s frames_sent=%llu\n",
                f[0], f[1], f[2], a[0], a[1], a[2], vesica::fp::to_string(arm.node().state()),
                vesica::fp::to_string(arm.node().latched_fault()),
                static_cast<unsigned long long>(arm.frames_sent()));
    std::fflush(stdout);
  }
  return 0;
}
