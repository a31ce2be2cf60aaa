// Measures how the arm link behaves on this host: two vesica-armsim processes on UDP loopback and
// one 1 kHz bridge thread ticking both arms (as the trainer's haptic thread does), for a fixed
// time. Not a test (its figures depend on the machine and its load): the numbers that chose the
// bridge's loss timeout and node watchdog (docs/protocol.md, "Link timing on a loaded host") come
// from it, run under load by measure_link_under_load.sh.
//
//   arm_link_under_load ARMSIM_PATH SECONDS LOSS_TIMEOUT_MS WATCHDOG_MS
//
// Prints, per arm: how often the silence between joint states passed each threshold (the link
// losses a loss timeout of that size would have seen), the same for the bridge's gaps between
// ticks (what the node's watchdog sees, less the network), and the real link losses and watchdog
// faults at the given settings.
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "armsim_process.h"
#include "device/arm_supervisor.h"
#include "device/can_arm.h"

namespace {

using namespace std::chrono_literals;
using vesica::device::CanArm;
namespace fp = vesica::fp;

constexpr std::array<int, 7> kThresholds_ms{5, 10, 20, 50, 100, 200, 500};

/// Counts, for each threshold, the episodes in which a running silence first exceeded it.
struct GapCounter {
  std::array<std::uint64_t, kThresholds_ms.size()> over{};
  std::int64_t longest_ns = 0;
  std::int64_t current_ns = 0;
  void Observe(std::int64_t silence_ns) {
    for (std::size_t i = 0; i < kThresholds_ms.size(); ++i) {
      const std::int64_t th = std::int64_t{kThresholds_ms[i]} * 1'000'000;
      if (silence_ns > th && current_ns <= th) ++over[i];
    }
    current_ns = silence_ns;
    longest_ns = std::max(longest_ns, silence_ns);
  }
  std::string Text(double minutes) const {
    std::string out;
    char buf[64];
    for (std::size_t i = 0; i < kThresholds_ms.size(); ++i) {
      std::snprintf(buf, sizeof buf, " >%dms:%.1f/min", kThresholds_ms[i], static_cast<double>(over[i]) / minutes);
      out += buf;
    }
    std::snprintf(buf, sizeof buf, " longest:%.1fms", 1e-6 * static_cast<double>(longest_ns));
    return out + buf;
  }
};

struct ArmUnderTest {
  std::unique_ptr<fp::UdpTransport> host;
  std::unique_ptr<CanArm> arm;
  vesica::device::testing::ArmsimProcess process;
  GapCounter state_silence;
  std::int64_t last_state_ns = -1;
  std::uint32_t watchdog_faults = 0;
  std::uint32_t emergencies_seen = 0;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: %s ARMSIM_PATH SECONDS LOSS_TIMEOUT_MS WATCHDOG_MS\n", argv[0]);
    return 2;
  }
  const std::string armsim = argv[1];
  const double seconds = std::atof(argv[2]);
  const int loss_ms = std::atoi(argv[3]);
  const int watchdog_ms = std::atoi(argv[4]);
  if (!(seconds > 0) || loss_ms <= 0 || watchdog_ms <= 0) {
    std::fprintf(stderr, "SECONDS, LOSS_TIMEOUT_MS and WATCHDOG_MS must be > 0\n");
    return 2;
  }

  std::array<ArmUnderTest, 2> arms;
  for (int i = 0; i < 2; ++i) {
    ArmUnderTest& a = arms[static_cast<std::size_t>(i)];
    const std::uint16_t arm_port = vesica::device::testing::FreeUdpPort();
    std::string error;
    a.host = fp::UdpTransport::open({.local_port = 0, .remote_port = arm_port}, error);
    if (!a.host) {
      std::fprintf(stderr, "cannot open the bridge's UDP port: %s\n", error.c_str());
      return 1;
    }
    if (!a.process.Start(armsim,
                         {"--node-id", std::to_string(i + 1), "--local-port", std::to_string(arm_port), "--remote-port",
                          std::to_string(a.host->local_port()), "--log-level", "warn", "--hand", "figure8"})) {
      std::fprintf(stderr, "cannot start %s\n", armsim.c_str());
      return 1;
    }
    vesica::device::CanArmConfig config;
    config.node_id = static_cast<std::uint8_t>(i + 1);
    config.loss_timeout = std::chrono::milliseconds(loss_ms);
    config.node_watchdog_timeout = std::chrono::milliseconds(watchdog_ms);
    a.arm = std::make_unique<CanArm>(*a.host, config);
    a.arm->Open();
  }

  // One thread ticks both arms at 1 kHz on an absolute grid, as the trainer's haptic loop does;
  // a supervisor per arm clears watchdog faults as the trainer's bridge does.
  std::array<std::unique_ptr<vesica::device::ArmSupervisor>, 2> supervisors;
  for (std::size_t i = 0; i < 2; ++i) {
    vesica::device::ArmSupervisorConfig sc;
    sc.name = i == 0 ? "left arm" : "right arm";
    supervisors[i] = std::make_unique<vesica::device::ArmSupervisor>(*arms[i].arm, sc);
  }
  GapCounter tick_gaps;
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const auto warmup_end = start + 2s;  // the handshake and the first enable are not measured
  const auto end = warmup_end + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  auto next = start;
  auto last_tick = start;
  std::uint64_t ticks = 0;
  while (Clock::now() < end) {
    const auto now = Clock::now();
    const bool measuring = now >= warmup_end;
    if (measuring) tick_gaps.Observe((now - last_tick).count());
    last_tick = now;
    for (std::size_t i = 0; i < 2; ++i) {
      ArmUnderTest& a = arms[i];
      a.arm->Tick();
      supervisors[i]->Tick(a.host->now());
      const std::int64_t t = a.host->now().count();
      const std::int64_t stamp = a.arm->GetToolState().timestamp_ns;
      if (stamp >= 0 && stamp != a.last_state_ns) a.last_state_ns = stamp;
      if (measuring && a.last_state_ns >= 0) a.state_silence.Observe(t - a.last_state_ns);
      const std::uint32_t em = a.arm->emergency_count();
      if (em != a.emergencies_seen) {
        a.emergencies_seen = em;
        if (measuring && a.arm->last_emergency() == fp::FaultCode::CommandWatchdog) ++a.watchdog_faults;
      }
    }
    ++ticks;
    next += 1ms;
    if (Clock::now() > next + 1ms) next = Clock::now();
    std::this_thread::sleep_until(next);
  }
  const double minutes = seconds / 60.0;
  double load1 = 0;
  if (FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf", &load1) != 1) load1 = -1;
    std::fclose(f);
  }
  std::printf("measured %.0f s, load average (1 min) at the end %.2f, bridge ticks %llu\n", seconds, load1,
              static_cast<unsigned long long>(ticks));
  std::printf("bridge tick gaps:%s\n", tick_gaps.Text(minutes).c_str());
  for (std::size_t i = 0; i < 2; ++i) {
    const ArmUnderTest& a = arms[i];
    const vesica::device::ArmReport r = supervisors[i]->Report();
    std::printf("arm %zu state silences:%s\n", i + 1, a.state_silence.Text(minutes).c_str());
    std::printf(
        "arm %zu at loss timeout %d ms, watchdog %d ms: link losses %.1f/min, watchdog faults %.1f/min, "
        "automatic resets %u, status now '%s'\n",
        i + 1, loss_ms, watchdog_ms, a.arm->link_loss_count() / minutes, a.watchdog_faults / minutes,
        r.automatic_fault_resets, r.text.c_str());
  }
  return 0;
}
