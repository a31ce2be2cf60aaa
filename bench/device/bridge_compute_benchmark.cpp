// Host-side cost of the device loop: force mapping, and one simulated millisecond of the
// virtual-bus rig (bus + emulator at 10 kHz + one bridge tick).
#include <benchmark/benchmark.h>

#include "device/arm_actuation.h"
#include "tests/device/bridge_rig.h"

namespace vesica::device {
namespace {

void BM_TipForceToMotorCurrents(benchmark::State& state) {
  const ArmActuation a = ArmActuation::Nominal();
  ArmJoints q{0.2, -0.1, 0.3, 0.12};
  Eigen::Vector3d f(1.0, -0.5, 1.5);
  for (auto _ : state) {
    benchmark::DoNotOptimize(TipForceToMotorCurrents(q, f, a));
    q.yaw_rad += 1e-9;
  }
}
BENCHMARK(BM_TipForceToMotorCurrents);

void BM_VirtualBusRigOneMillisecond(benchmark::State& state) {
  testing::BridgeRig rig;
  rig.arm->Open();
  rig.Run(0.2);
  rig.arm->SetTipForce(Eigen::Vector3d(1.0, -0.5, 1.5));
  for (auto _ : state) rig.Run(0.001);
  state.counters["bus_load"] = rig.bus.load();
}
BENCHMARK(BM_VirtualBusRigOneMillisecond)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace vesica::device
