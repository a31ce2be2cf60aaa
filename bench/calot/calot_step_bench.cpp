// One physics step of Calot's triangle (docs/calot.md): the four tubes of the default scenario
// (about 20 nodes each at 2.5 mm) following a moving neck, and the fat layer's update with the
// hook burning and a jaw pushing. The dissection scene's whole step has 3 ms (issue 36).
#include <benchmark/benchmark.h>

#include <cmath>

#include "physics/calot/fat_layer.h"
#include "physics/calot/triangle_structures.h"

namespace vesica::physics::calot {
namespace {

Eigen::Vector3d Neck(const TriangleStructures& s, int step) {
  const double phase = 0.02 * step;
  return s.description().p_Neck_W_m + 0.005 * Eigen::Vector3d(std::sin(phase), 1.0 - std::cos(phase), 0.0);
}

void BM_TriangleTubesStep(benchmark::State& state) {
  TriangleStructures s(DefaultTriangleDescription());
  int nodes = 0;
  for (const TubePiece& p : s.pieces()) nodes += p.rod.num_nodes();
  int step = 0;
  for (auto _ : state) {
    s.Step(Neck(s, ++step));
    benchmark::DoNotOptimize(s.NeckForce_N());
  }
  state.counters["nodes"] = nodes;
}
BENCHMARK(BM_TriangleTubesStep)->Unit(benchmark::kMicrosecond);

void BM_FatLayerUpdate(benchmark::State& state) {
  TriangleStructures s(DefaultTriangleDescription());
  FatLayer fat(DefaultFatLayerDescription(s.description()), s);
  for (auto _ : state) {
    fat.Update(s);
    benchmark::DoNotOptimize(fat.UncoveredFraction(0));
  }
  state.counters["cells"] = static_cast<double>(fat.cells().size());
}
BENCHMARK(BM_FatLayerUpdate)->Unit(benchmark::kMicrosecond);

// What the scene adds a step: tubes, the hook burning the triangle's middle, a jaw tip pushing,
// the layer following, and the reports the metrics read.
void BM_TriangleAndFatLayerStep(benchmark::State& state) {
  TriangleStructures s(DefaultTriangleDescription());
  FatLayer fat(DefaultFatLayerDescription(s.description()), s);
  const auto& corners = fat.description().corners_m;
  const Eigen::Vector3d middle = (corners[0] + corners[1] + corners[2]) / 3.0;
  int step = 0;
  for (auto _ : state) {
    ++step;
    s.Step(Neck(s, step));
    s.PushByTip(middle + Eigen::Vector3d(0.0, 0.0, 0.004), 0.0015);
    fat.Burn(middle + 0.004 * Eigen::Vector3d(std::sin(0.01 * step), 0.0, 0.0), 0.002, 30.0, 0.005);
    fat.Push(middle + Eigen::Vector3d(0.003, 0.003, 0.0), 0.0015);
    fat.Update(s);
    double uncovered = 0.0;
    for (int t = 0; t < s.num_tubes(); ++t) uncovered += fat.UncoveredFraction(t);
    benchmark::DoNotOptimize(uncovered + fat.TriangleClearedFraction());
    benchmark::DoNotOptimize(s.Leaks());
  }
}
BENCHMARK(BM_TriangleAndFatLayerStep)->Unit(benchmark::kMicrosecond);

void BM_FatLayerBuild(benchmark::State& state) {
  TriangleStructures s(DefaultTriangleDescription());
  for (auto _ : state) {
    FatLayer fat(DefaultFatLayerDescription(s.description()), s);
    benchmark::DoNotOptimize(fat.cells().size());
  }
}
BENCHMARK(BM_FatLayerBuild)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace vesica::physics::calot
