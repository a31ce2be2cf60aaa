// Codec cost per frame, node cost per frame + tick, and bus load on the virtual bus.
#include <benchmark/benchmark.h>

#include <vector>

#include "firmware_protocol/codec/codec.h"
#include "firmware_protocol/node/node.h"
#include "firmware_protocol/transport/virtual_bus.h"

using namespace std::chrono_literals;

namespace vesica::fp {
namespace {

void BM_EncodeJointState(benchmark::State& state) {
  JointState js{1, 0, NodeState::Operational, true, Limiter::None, {0.5f, -0.25f, 0.12f}};
  CanFrame f;
  for (auto _ : state) {
    ++js.counter;
    benchmark::DoNotOptimize(encode(js, f));
    benchmark::DoNotOptimize(f);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_EncodeJointState);

void BM_DecodeJointState(benchmark::State& state) {
  CanFrame f;
  encode(JointState{1, 0, NodeState::Operational, true, Limiter::None, {0.5f, -0.25f, 0.12f}}, f);
  Message m;
  for (auto _ : state) {
    benchmark::DoNotOptimize(f);
    benchmark::DoNotOptimize(decode(f, m));
    benchmark::DoNotOptimize(m);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DecodeJointState);

void BM_DecodeCurrentCommand(benchmark::State& state) {
  CanFrame f;
  encode(CurrentCommand{2, 7, CommandMode::MotorCurrent, {1.0f, -2.0f, 0.5f}}, f);
  Message m;
  for (auto _ : state) {
    benchmark::DoNotOptimize(f);
    benchmark::DoNotOptimize(decode(f, m));
    benchmark::DoNotOptimize(m);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DecodeCurrentCommand);

void BM_DecodeUnknownId(benchmark::State& state) {  // the cost of rejecting garbage
  CanFrame f;
  f.id = 0x7F0;
  f.len = 8;
  Message m;
  for (auto _ : state) {
    benchmark::DoNotOptimize(f);
    benchmark::DoNotOptimize(decode(f, m));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DecodeUnknownId);

struct BenchHardware {
  HardwareSample sample;
  JointArray applied{};
  std::vector<std::uint8_t> storage;  // empty: blank flash
  HardwareSample sense() { return sample; }
  void apply_currents(const JointArray& a) { applied = a; }
  bool storage_read(std::size_t offset, std::uint8_t* dst, std::size_t n) {
    if (storage.size() < offset + n) return false;
    for (std::size_t i = 0; i < n; ++i) dst[i] = storage[offset + i];
    return true;
  }
  bool storage_write(std::size_t, const std::uint8_t*, std::size_t) { return true; }
};

// One 1 kHz firmware cycle: receive a command, answer JointState, run the control tick.
void BM_NodeCommandAndTick(benchmark::State& state) {
  BenchHardware hw;
  Node<BenchHardware> node(hw, 1);
  node.boot(0);
  CanFrame f;
  encode(Hello{1, kProtocolMajor, kProtocolMinor}, f);
  node.on_frame(f, 0);
  encode(Nmt{NmtCommand::Start, 0}, f);
  node.on_frame(f, 0);
  encode(Control{1, 0, ControlCommand::Enable}, f);
  node.on_frame(f, 0);
  std::uint64_t now_us = 0;
  std::uint8_t counter = 0;
  CanFrame out;
  for (auto _ : state) {
    now_us += 1000;
    encode(CurrentCommand{1, counter++, CommandMode::MotorCurrent, {0.5f, -0.5f, 1.0f}}, f);
    node.on_frame(f, now_us);
    node.tick(now_us);
    while (node.pop_tx(out)) benchmark::DoNotOptimize(out);
  }
  benchmark::DoNotOptimize(hw.applied);
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_NodeCommandAndTick);

// Two arms at 1 kHz for one simulated second on the virtual bus; reports the measured bus load
// and how fast the bus simulates (simulated seconds per wall second).
void BM_VirtualBusTwoArmsOneSecond(benchmark::State& state) {
  double load = 0;
  for (auto _ : state) {
    VirtualClock clock;
    VirtualBus bus(clock);
    auto& host = bus.attach("host");
    BenchHardware hw[2];
    Node<BenchHardware> n1(hw[0], 1), n2(hw[1], 2);
    Node<BenchHardware>* nodes[2] = {&n1, &n2};
    VirtualBusEndpoint* ep[2] = {&bus.attach("arm1"), &bus.attach("arm2")};
    ParameterStore p;  // node 2's id comes from its stored parameter image
    p.set_internal(param::kNodeId, 2);
    hw[1].storage.resize(ParameterStore::kImageSize);
    p.serialize(hw[1].storage.data(), hw[1].storage.size());
    n1.boot(0);
    n2.boot(0);
    bus.reset_load();
    std::uint8_t counter = 0;
    for (int ms = 0; ms < 1000; ++ms) {
      for (std::uint8_t a = 1; a <= 2; ++a) {
        CanFrame f;
        encode(CurrentCommand{a, counter, CommandMode::MotorCurrent, {0.1f, 0.2f, 0.3f}}, f);
        host.send(f, clock.now() + 1ms);
      }
      ++counter;
      for (int sub = 0; sub < 4; ++sub) {
        bus.advance(250us);
        for (int a = 0; a < 2; ++a) {
          TimedFrame rx;
          const auto now_us = static_cast<std::uint64_t>(clock.now().count() / 1000);
          while (ep[a]->receive(rx)) nodes[a]->on_frame(rx.frame, now_us);
          nodes[a]->tick(now_us);
          CanFrame out;
          while (nodes[a]->pop_tx(out)) ep[a]->send(out, clock.now() + 1ms);
        }
      }
      TimedFrame rx;
      while (host.receive(rx)) benchmark::DoNotOptimize(rx);
    }
    load = bus.load();
  }
  state.counters["bus_load_percent"] = 100.0 * load;
  state.counters["sim_seconds_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_VirtualBusTwoArmsOneSecond)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace vesica::fp
