// The 1 kHz bridge loop against vesica-armsim in another process over CAN-over-UDP loopback:
// loop period p50/p99 and command -> joint-state round trip, over a 10 s window.
#include <chrono>
#include <string>
#include <thread>
#include <variant>

#include <benchmark/benchmark.h>

#include "device/bridge_loop.h"
#include "device/can_arm.h"
#include "device/latency_statistics.h"
#include "firmware_protocol/codec/codec.h"
#include "tests/device/armsim_process.h"

namespace vesica::device {
namespace {

using namespace std::chrono_literals;

void BM_BridgeLoopOverUdp(benchmark::State& state) {
  const int seconds = static_cast<int>(state.range(0));
  for (auto _ : state) {
    const std::uint16_t arm_port = testing::FreeUdpPort();
    std::string error;
    auto host = fp::UdpTransport::open({.local_port = 0, .remote_port = arm_port}, error);
    if (!host || arm_port == 0) {
      state.SkipWithError(("UDP: " + error).c_str());
      return;
    }
    const int realtime_priority = static_cast<int>(state.range(1));
    testing::ArmsimProcess armsim;
    if (!armsim.Start(VESICA_ARMSIM_PATH, {"--local-port", std::to_string(arm_port), "--remote-port",
                                           std::to_string(host->local_port()), "--duration-s",
                                           std::to_string(seconds + 3), "--log-level", "warn",
                                           "--realtime-priority", std::to_string(realtime_priority)})) {
      state.SkipWithError("cannot start vesica-armsim");
      return;
    }
    CanArmConfig config;  // no real-time scheduling here: tolerate multi-ms gaps
    config.node_watchdog_timeout = 50ms;
    config.loss_timeout = 100ms;
    CanArm arm(*host, config);
    arm.Open();
    BridgeLoop loop(arm);
    loop.set_realtime_priority(realtime_priority);
    loop.Start();
    for (int i = 0; i < 200 && arm.Status() != DeviceStatus::kOk; ++i) std::this_thread::sleep_for(10ms);
    if (arm.Status() != DeviceStatus::kOk) {
      loop.Stop();
      state.SkipWithError("arm never reached kOk");
      return;
    }
    arm.SetTipForce(Eigen::Vector3d(0.8, -0.4, 1.2));
    std::this_thread::sleep_for(200ms);
    arm.ResetStatistics();
    const std::uint64_t overruns_before = loop.overruns();
    std::this_thread::sleep_for(std::chrono::seconds(seconds));
    const auto period = arm.loop_period();
    const auto rtt = arm.round_trip();
    const bool ok = arm.Status() == DeviceStatus::kOk;
    loop.Stop();
    armsim.Finish(nullptr);
    state.SetIterationTime(seconds);
    state.counters["period_p50_us"] = period.p50_ns / 1e3;
    state.counters["period_p99_us"] = period.p99_ns / 1e3;
    state.counters["period_max_us"] = period.max_ns / 1e3;
    state.counters["period_jitter_us"] = period.jitter_ns / 1e3;
    state.counters["rtt_p50_us"] = rtt.p50_ns / 1e3;
    state.counters["rtt_p99_us"] = rtt.p99_ns / 1e3;
    state.counters["rtt_max_us"] = rtt.max_ns / 1e3;
    state.counters["ticks"] = static_cast<double>(period.count);
    state.counters["answered"] = static_cast<double>(rtt.count);
    state.counters["overruns"] = static_cast<double>(loop.overruns() - overruns_before);
    state.counters["stayed_ok"] = ok ? 1 : 0;
    state.counters["sched_fifo"] = realtime_priority > 0 && loop.realtime_error().empty() ? 1 : 0;
  }
}
// Args: seconds, SCHED_FIFO priority of the loop thread (0: normal scheduling).
BENCHMARK(BM_BridgeLoopOverUdp)->Args({10, 0})->Args({10, 80})->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);

// Wire round trip without the 1 kHz tick in the way: SYNC out, busy-wait for the arm's joint state
// (UDP loopback both ways + vesica-armsim's receive and reply). The UDP transport stamps frames
// when they are read, so the bridge loop above sees replies only at its next tick.
void BM_SyncRoundTripOverUdp(benchmark::State& state) {
  const std::uint16_t arm_port = testing::FreeUdpPort();
  std::string error;
  auto host = fp::UdpTransport::open({.local_port = 0, .remote_port = arm_port}, error);
  testing::ArmsimProcess armsim;
  if (!host || arm_port == 0 ||
      !armsim.Start(VESICA_ARMSIM_PATH, {"--local-port", std::to_string(arm_port), "--remote-port",
                                         std::to_string(host->local_port()), "--duration-s", "60", "--log-level",
                                         "warn"})) {
    state.SkipWithError("cannot start vesica-armsim on UDP");
    return;
  }
  std::this_thread::sleep_for(300ms);  // let it boot
  fp::TimedFrame rx;
  while (host->receive(rx)) {
  }
  LatencyStatistics rtt(1 << 16);
  std::uint8_t counter = 0;
  std::uint64_t timeouts = 0;
  for (auto _ : state) {
    fp::CanFrame f;
    fp::encode(fp::Sync{counter++}, f);
    const auto t0 = std::chrono::steady_clock::now();
    host->send(f, host->now() + 1ms);
    bool answered = false;
    while (!answered && std::chrono::steady_clock::now() - t0 < 50ms) {
      host->wait(1ms);
      while (host->receive(rx)) {
        fp::Message m;
        if (fp::decode(rx.frame, m) == fp::DecodeError::None && std::holds_alternative<fp::JointState>(m)) answered = true;
      }
    }
    const auto dt = std::chrono::steady_clock::now() - t0;
    if (!answered) ++timeouts;
    rtt.Add(std::chrono::duration_cast<std::chrono::nanoseconds>(dt).count());
    state.SetIterationTime(std::chrono::duration<double>(dt).count());
  }
  const auto s = rtt.Summarize();
  state.counters["rtt_p50_us"] = s.p50_ns / 1e3;
  state.counters["rtt_p99_us"] = s.p99_ns / 1e3;
  state.counters["rtt_max_us"] = s.max_ns / 1e3;
  state.counters["timeouts"] = static_cast<double>(timeouts);
}
BENCHMARK(BM_SyncRoundTripOverUdp)->Iterations(5000)->UseManualTime()->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace vesica::device
