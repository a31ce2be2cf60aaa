// Measures what a calibration session over UDP goes through on this host: one vesica-armsim
// process (--random-arm SEED) and the calibration library's whole-arm calibration (ArmCalibrator,
// as vesica-calibrate runs it) in real time. Not a test (its figures depend on the machine and its
// load): the numbers that chose the calibration session's watchdog and the tool's loss timeout
// (docs/protocol.md section 11, "Watchdog in a calibration session") come from it, run under load
// by measure_calibration_under_load.sh.
//
//   calibration_under_load ARMSIM_PATH SEED LOSS_TIMEOUT_MS
//
// Prints the gaps between the host's commands (what the node's watchdog sees, less the network and
// the emulator's own stalls), the silences between joint states at the host (those stalls
// included), how the calibration ended, its numbers against the arm's ground truth, and the
// node's fault history.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <thread>

#include "../device/armsim_process.h"
#include "device/calibration/arm_calibrator.h"
#include "firmware_protocol/emulator/arm_ground_truth.h"
#include "firmware_protocol/node/parameter_table.h"

namespace {

namespace fp = vesica::fp;
namespace cal = vesica::device::calibration;
using namespace std::chrono_literals;

constexpr std::array<int, 9> kThresholds_ms{2, 3, 5, 10, 20, 50, 100, 200, 500};

/// Episodes in which a gap exceeded each threshold, and the longest.
struct GapCounter {
  std::array<std::uint64_t, kThresholds_ms.size()> over{};
  std::int64_t longest_ns = 0;
  std::int64_t last_ns = -1;
  std::uint64_t count = 0;
  void Mark(std::int64_t t_ns) {
    if (last_ns >= 0) {
      const std::int64_t gap = t_ns - last_ns;
      for (std::size_t i = 0; i < kThresholds_ms.size(); ++i)
        if (gap > std::int64_t{kThresholds_ms[i]} * 1'000'000) ++over[i];
      longest_ns = std::max(longest_ns, gap);
    }
    last_ns = t_ns;
    ++count;
  }
  std::string Text() const {
    std::string out;
    char buf[64];
    for (std::size_t i = 0; i < kThresholds_ms.size(); ++i) {
      std::snprintf(buf, sizeof buf, " >%dms:%llu", kThresholds_ms[i], static_cast<unsigned long long>(over[i]));
      out += buf;
    }
    std::snprintf(buf, sizeof buf, " longest:%.1fms (of %llu)", 1e-6 * static_cast<double>(longest_ns),
                  static_cast<unsigned long long>(count));
    return out + buf;
  }
};

/// The host's transport, timing every CurrentCommand it sends and every JointState it receives.
class TimingTransport final : public fp::Transport {
 public:
  explicit TimingTransport(fp::Transport& inner) : inner_(inner) {}
  fp::SendStatus send(const fp::CanFrame& f, fp::Nanoseconds deadline) override {
    const fp::SendStatus s = inner_.send(f, deadline);
    if ((f.id & 0x780) == 0x200 && (f.id & 0x7F) != 0) commands.Mark(inner_.now().count());
    return s;
  }
  bool receive(fp::TimedFrame& out) override {
    if (!inner_.receive(out)) return false;
    if ((out.frame.id & 0x780) == 0x180 && (out.frame.id & 0x7F) != 0) states.Mark(inner_.now().count());
    return true;
  }
  bool poll_event(fp::BusEvent& out) override { return inner_.poll_event(out); }
  bool wait(fp::Nanoseconds timeout) override { return inner_.wait(timeout); }
  fp::Nanoseconds now() const override { return inner_.now(); }
  fp::BusState state() const override { return inner_.state(); }
  fp::TransportStats stats() const override { return inner_.stats(); }

  GapCounter commands;
  GapCounter states;

 private:
  fp::Transport& inner_;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: %s ARMSIM_PATH SEED LOSS_TIMEOUT_MS\n", argv[0]);
    return 2;
  }
  const std::string armsim = argv[1];
  const std::uint64_t seed = std::strtoull(argv[2], nullptr, 10);
  const int loss_ms = std::atoi(argv[3]);
  if (seed == 0 || loss_ms <= 0) {
    std::fprintf(stderr, "SEED and LOSS_TIMEOUT_MS must be > 0\n");
    return 2;
  }
  const std::uint16_t arm_port = vesica::device::testing::FreeUdpPort();
  std::string error;
  auto udp = fp::UdpTransport::open({.local_port = 0, .remote_port = arm_port}, error);
  if (!udp) {
    std::fprintf(stderr, "cannot open the tool's UDP port: %s\n", error.c_str());
    return 1;
  }
  vesica::device::testing::ArmsimProcess process;
  if (!process.Start(armsim, {"--node-id", "1", "--local-port", std::to_string(arm_port), "--remote-port",
                              std::to_string(udp->local_port()), "--log-level", "warn", "--random-arm",
                              std::to_string(seed), "--report"})) {
    std::fprintf(stderr, "cannot start %s\n", armsim.c_str());
    return 1;
  }
  std::this_thread::sleep_for(300ms);  // the arm boots
  TimingTransport bus(*udp);
  cal::CalibrationLinkConfig config;
  config.loss_timeout = std::chrono::milliseconds(loss_ms);
  config.reply_timeout = 2s;
  cal::CalibrationLink link(
      bus,
      [&bus](fp::Nanoseconds until) {
        while (bus.now() < until) bus.wait(until - bus.now());
      },
      config);
  cal::CalibrationPlan plan;
  const auto wall0 = std::chrono::steady_clock::now();
  const cal::CalibrationResult r = cal::ArmCalibrator(link, plan).Run();
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  std::printf("load average: %s", [] {
    std::FILE* f = std::fopen("/proc/loadavg", "r");
    static char b[128] = "?\n";
    if (f) {
      if (!std::fgets(b, sizeof b, f)) b[0] = 0;
      std::fclose(f);
    }
    return b;
  }());
  std::printf("calibration: %s after %.1f s%s%s\n", r.saved ? "saved" : "ABORTED", wall_s,
              r.saved ? "" : (" in step " + r.failed_step + ": ").c_str(), r.saved ? "" : r.message.c_str());
  std::printf("host command gaps: %s\n", bus.commands.Text().c_str());
  std::printf("joint-state silences at the host: %s\n", bus.states.Text().c_str());
  for (int j = 0; j < 3; ++j) {
    std::printf("joint %d friction segments (velocity, torque):", j);
    for (const auto& seg : r.joint[j].friction_segments) std::printf(" (%.4f, %.5f)", seg.velocity, seg.torque);
    std::printf("\n");
  }
  std::printf("gravity holds (angle, up, down):");
  for (const auto& h : r.gravity_holds)
    std::printf(" (%.3f, %.5f, %.5f)", h.angle_rad, h.breakaway_up, h.breakaway_down);
  std::printf("\n");
  if (r.saved) {
    const auto truth = vesica::fp::emulator::RandomArm(seed);
    for (int j = 0; j < 3; ++j) {
      const double unit = j < 2 ? 180.0 / 3.14159265358979 : 1000.0;
      const double nominal = j < 2 ? 0.0302 : 0.0276;
      const double kt = truth.torque_constant_ratio(j, nominal);
      std::printf("joint %d: direction %s, stops %+.3f %+.3f %s, coulomb %+.1f %%, viscous %+.1f %%\n", j,
                  r.joint[j].direction == truth.plant.encoder[j].direction ? "right" : "WRONG",
                  unit * (r.joint[j].lower_stop - truth.lower_stop(j)),
                  unit * (r.joint[j].upper_stop - truth.upper_stop(j)), j < 2 ? "deg" : "mm",
                  100.0 * (r.joint[j].coulomb * kt / truth.coulomb(j) - 1.0),
                  100.0 * (r.joint[j].viscous * kt / truth.viscous(j) - 1.0));
    }
    // Pitch's holding torque (minus gravity's) in the node's units, worst over the range.
    const double kt = truth.torque_constant_ratio(1, 0.0302);
    const double gs = -truth.plant.pitch_gravity_sin_Nm / kt, gc = -truth.plant.pitch_gravity_cos_Nm / kt;
    double worst = 0.0;
    for (double a = truth.lower_stop(1); a <= truth.upper_stop(1); a += 0.01)
      worst = std::max(worst, std::abs(r.gravity_sin * std::sin(a) + r.gravity_cos * std::cos(a) -
                                       (gs * std::sin(a) + gc * std::cos(a))));
    std::printf("gravity: worst %.1f %% of its amplitude\n", 100.0 * worst / std::hypot(gs, gc));
  }
  // The node's own account: its fault history (command_watchdog entries are the stalls it saw).
  try {
    const std::uint32_t faults = link.ReadU32(fp::param::kFaultHistoryCount);
    std::printf("node fault history: %u fault(s)", faults);
    for (std::uint16_t k = 0; k < std::min<std::uint32_t>(faults, fp::param::kFaultHistoryDepth); ++k)
      std::printf(" 0x%08X", link.ReadU32(static_cast<std::uint16_t>(fp::param::kFaultHistory + k)));
    std::printf("\n");
  } catch (const cal::CalibrationAbort& e) {
    std::printf("node fault history: not read (%s)\n", e.what());
  }
  process.Kill(SIGTERM);
  std::string report;
  process.Finish(&report);
  std::printf("armsim: %s", report.c_str());
  return r.saved ? 0 : 1;
}
