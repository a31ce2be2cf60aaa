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
#include <string>

#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "app/armsim/armsim_transport.h"
#include "firmware_protocol/emulator/arm_emulator.h"

namespace {

std::atomic<bool> g_stop{false};
void OnSignal(int) { g_stop.store(true); }

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
  app.add_option("--local-port", udp.local_port, "UDP port this arm listens on")->check(CLI::Range(1, 65535));
  app.add_option("--remote-host", udp.remote_host, "host bridge address (IPv4)");
  app.add_option("--remote-port", udp.remote_port, "host bridge UDP port")->check(CLI::Range(1, 65535));
  app.add_option("--duration-s", duration_s, "stop after this many seconds (0: until SIGINT/SIGTERM)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--node-id", node_id, "CAN node id of this arm")->check(CLI::Range(1, 127));
  app.add_option("--tick-us", tick_us, "node and plant step, microseconds")->check(CLI::Range(20, 1000));
  app.add_option("--hand-x-mm", hand_x_mm, "hand target, trocar frame x, mm");
  app.add_option("--hand-y-mm", hand_y_mm, "hand target, trocar frame y, mm");
  app.add_option("--depth-mm", depth_mm, "park insertion depth and hand target depth, mm")
      ->check(CLI::Range(20.0, 250.0));
  app.add_option("--realtime-priority", realtime_priority, "SCHED_FIFO priority, 0: normal scheduling")
      ->check(CLI::Range(0, 99));
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error");
  app.add_flag("--report", report, "print the final plant state as one key=value line on stdout");
  CLI11_PARSE(app, argc, argv);
  spdlog::set_level(spdlog::level::from_str(log_level));

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

  const double depth = depth_mm * 1e-3;
  const emu::Joint4 q0{0.0, 0.0, 0.0, depth};
  emu::ArmEmulator::Config config;
  config.tick_period = std::chrono::microseconds(tick_us);
  config.node_id = static_cast<std::uint8_t>(node_id);
  config.board.park_position = {0.0f, 0.0f, static_cast<float>(depth)};
  emu::ArmEmulator arm(*transport, emu::ArmPlantParameters::Nominal(), q0, config);
  emu::HandTarget hold;
  hold.p_T = {hand_x_mm * 1e-3, hand_y_mm * 1e-3, depth};
  arm.plant().SetHandScript(emu::HandScript(hold));
  spdlog::info("vesica-armsim: node {} listening on UDP {} -> {}:{}", arm.node().node_id(), udp.local_port,
               udp.remote_host, udp.remote_port);

  const auto start = transport->now();
  auto next_log = start;
  while (!g_stop.load()) {
    const auto now = transport->now();
    if (duration_s > 0 && now - start >= std::chrono::duration<double>(duration_s)) break;
    arm.RunUntil(now);
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
