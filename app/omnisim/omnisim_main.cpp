// vesica-omnisim: an emulated Phantom Omni (6-DOF stylus pose in, 3-DOF force out) in its own
// process, speaking the Omni datagram protocol (docs/omni.md) over UDP on loopback, with a
// scripted hand holding the stylus through a spring, so the trainer's force moves it.
#include <sched.h>
#include <spdlog/spdlog.h>
#include <time.h>

#include <CLI/CLI.hpp>
#include <array>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "app/omnisim/hand_script.h"
#include "app/omnisim/hand_spring.h"
#include "device/stylus/omni_datagram.h"
#include "device/stylus/stylus_capabilities.h"
#include "device/stylus/stylus_force.h"
#include "device/stylus/udp_datagram_socket.h"

namespace {

std::atomic<bool> g_stop{false};
void OnSignal(int) { g_stop.store(true); }

std::int64_t SteadyNowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

}  // namespace

int main(int argc, char** argv) {
  namespace dev = vesica::device;
  CLI::App app{"vesica-omnisim: emulated Phantom Omni stylus over UDP (docs/omni.md)"};
  int port = 21000;
  int host_port = 21001;
  std::string host = "127.0.0.1";
  std::vector<std::string> hand = {"biopsy"};
  double duration_s = 0.0;
  double rate_hz = 1000.0;
  double force_timeout_ms = 50.0;
  vesica::app::HandSpringParameters spring;
  int realtime_priority = 0;
  bool report = false;
  std::string log_level = "info";
  app.add_option("--port", port, "UDP port this device listens on for force datagrams")->check(CLI::Range(1, 65535));
  app.add_option("--host", host, "trainer's address (IPv4)");
  app.add_option("--host-port", host_port, "trainer's UDP port for pose datagrams")->check(CLI::Range(1, 65535));
  app.add_option("--hand", hand,
                 "what the hand does: 'biopsy' (built in: approach, insert 50 mm, hold with a biopsy click, "
                 "withdraw; 6.5 s, repeating), 'hold' (still at the workspace centre), or 'recording FILE' "
                 "(a stylus recording, docs/omni.md, repeating)")
      ->expected(1, 2);
  app.add_option("--duration-s", duration_s, "stop after this many seconds (0: until SIGINT/SIGTERM)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--rate-hz", rate_hz, "servo rate: pose datagrams per second")->check(CLI::Range(10.0, 10000.0));
  app.add_option("--force-timeout-ms", force_timeout_ms,
                 "no force datagram for this long: the emulated amplifiers render zero (as the Omni's driver does)")
      ->check(CLI::Range(1.0, 10000.0));
  app.add_option("--hand-stiffness-N-per-m", spring.stiffness_N_per_m, "grip stiffness")->check(CLI::Range(1.0, 1e5));
  app.add_option("--hand-mass-kg", spring.mass_kg, "stylus and hand mass at the tip")->check(CLI::Range(0.001, 10.0));
  app.add_option("--realtime-priority", realtime_priority, "SCHED_FIFO priority, 0: normal scheduling")
      ->check(CLI::Range(0, 99));
  app.add_flag("--report", report, "print counters and the final stylus state as one key=value line on stdout");
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error");
  std::string write_script;
  app.add_option("--write-script", write_script,
                 "write the hand's script (--hand) as a stylus recording to FILE and exit (docs/omni.md)");
  CLI11_PARSE(app, argc, argv);
  spdlog::set_level(spdlog::level::from_str(log_level));

  std::unique_ptr<vesica::app::HandScript> script;
  std::string hand_text;
  try {
    const std::string& mode = hand.at(0);
    if ((mode == "recording") != (hand.size() == 2))
      throw std::invalid_argument("--hand: 'recording' takes a FILE, 'biopsy' and 'hold' take nothing");
    if (mode == "biopsy") {
      script = std::make_unique<vesica::app::HandScript>(vesica::app::BuiltInBiopsyRecording());
      hand_text = "doing the built-in biopsy";
    } else if (mode == "hold") {
      dev::StylusRecording still;
      still.samples.push_back({0.0, dev::StylusState{}});
      script = std::make_unique<vesica::app::HandScript>(still);
      hand_text = "holding still";
    } else if (mode == "recording") {
      script = std::make_unique<vesica::app::HandScript>(dev::ReadStylusRecording(hand[1]));
      hand_text = "playing " + hand[1];
    } else {
      throw std::invalid_argument("--hand: unknown '" + mode + "' (biopsy, hold, recording FILE)");
    }
  } catch (const std::exception& e) {
    spdlog::error("vesica-omnisim: {}", e.what());
    return 2;
  }

  if (!write_script.empty()) {
    try {
      dev::WriteStylusRecording(write_script, script->Recording());
    } catch (const std::exception& e) {
      spdlog::error("vesica-omnisim: {}", e.what());
      return 2;
    }
    spdlog::info("vesica-omnisim: wrote the hand's script ({}) to {}", hand_text, write_script);
    return 0;
  }

  std::string error;
  auto socket = dev::UdpDatagramSocket::Open({"127.0.0.1", static_cast<std::uint16_t>(port)},
                                             {host, static_cast<std::uint16_t>(host_port)}, &error);
  if (!socket) {
    spdlog::error("vesica-omnisim: {}", error);
    return 2;
  }
  if (realtime_priority > 0) {
    sched_param param{};
    param.sched_priority = realtime_priority;
    if (sched_setscheduler(0, SCHED_FIFO, &param) != 0)
      spdlog::warn("vesica-omnisim: SCHED_FIFO priority {} refused ({}), running with normal scheduling",
                   realtime_priority, std::strerror(errno));
  }
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);

  const dev::StylusCapabilities caps = dev::PhantomOmniCapabilities();
  vesica::app::HandSpring stylus(spring, script->At(0.0).p_BTip_B);
  spdlog::info("vesica-omnisim: Omni emulator on UDP {} -> {}:{} at {} Hz, the hand {}", socket->local_port(), host,
               host_port, rate_hz, hand_text);

  const std::int64_t period_ns = static_cast<std::int64_t>(1e9 / rate_hz);
  const double dt_s = 1e-9 * static_cast<double>(period_ns);
  const std::int64_t start_ns = SteadyNowNs();
  std::int64_t next_ns = start_ns;
  std::int64_t last_force_ns = start_ns;
  Eigen::Vector3d force_N = Eigen::Vector3d::Zero();
  std::uint32_t sequence = 0;
  std::uint64_t forces_received = 0, rejected = 0, send_failures = 0;
  std::string last_rejection;
  std::array<std::uint8_t, 512> buffer{};
  double t_s = 0.0;
  while (!g_stop.load()) {
    const std::int64_t now_ns = SteadyNowNs();
    if (duration_s > 0 && now_ns - start_ns >= static_cast<std::int64_t>(duration_s * 1e9)) break;
    bool from_peer = false;
    for (long n; (n = socket->Receive(buffer, &from_peer)) >= 0;) {
      dev::OmniForceDatagram in;
      const auto bytes = std::span<const std::uint8_t>(buffer.data(), std::min<std::size_t>(n, buffer.size()));
      if (!from_peer) {
        ++rejected;
        last_rejection = "a datagram from another address than the trainer's";
      } else if (auto problem = dev::DecodeOmniForce(bytes, &in)) {
        ++rejected;
        last_rejection = *problem;
        spdlog::debug("vesica-omnisim: dropped: {}", *problem);
      } else {
        force_N = dev::SaturateForce(in.f_B, caps.device.max_force_N);
        last_force_ns = now_ns;
        ++forces_received;
      }
    }
    if (now_ns - last_force_ns > static_cast<std::int64_t>(force_timeout_ms * 1e6)) force_N.setZero();

    // One servo period of the hand and stylus; a host that fell far behind resynchronises.
    const dev::StylusState aim = script->At(t_s);
    stylus.Step(dt_s, aim.p_BTip_B, force_N);
    t_s += dt_s;
    dev::OmniPoseDatagram pose;
    pose.sequence = ++sequence;
    pose.buttons = aim.buttons;
    pose.timestamp_ns = SteadyNowNs();
    pose.p_BTip_B = dev::ClampToWorkspace(caps, stylus.position_m());
    pose.d_B = aim.d_B;
    const auto out = dev::EncodeOmniPose(pose);
    if (!socket->Send(out, &error) && ++send_failures == 1) spdlog::warn("vesica-omnisim: {}", error);

    next_ns += period_ns;
    if (SteadyNowNs() - next_ns > 50 * period_ns) next_ns = SteadyNowNs();
    const timespec deadline{static_cast<time_t>(next_ns / 1'000'000'000), static_cast<long>(next_ns % 1'000'000'000)};
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &deadline, nullptr);
  }
  if (report) {
    const Eigen::Vector3d& p = stylus.position_m();
    std::printf(
        "poses_sent=%u forces_received=%llu rejected=%llu force_N=%.6f,%.6f,%.6f position_m=%.6f,%.6f,%.6f "
        "last_rejection=\"%s\"\n",
        sequence, static_cast<unsigned long long>(forces_received), static_cast<unsigned long long>(rejected),
        force_N.x(), force_N.y(), force_N.z(), p.x(), p.y(), p.z(), last_rejection.c_str());
    std::fflush(stdout);
  }
  return 0;
}
