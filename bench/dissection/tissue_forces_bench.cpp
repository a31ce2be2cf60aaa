// Spring force evaluation and nodal distribution for ~200 connective-tissue springs (issue 6).
#include <benchmark/benchmark.h>

#include "physics/mesh/primitives.h"
#include "physics/tissue/spring_forces.h"

namespace vesica::physics {
namespace {

void BM_TissueForces(benchmark::State& state) {
  // 15 x 15 top vertices of a 42 x 42 x 6 mm box under a liver slab 3 mm above: 225 springs.
  const TetrahedralMesh gb = MakeBoxTetMesh({0.042, 0.042, 0.006}, {14, 14, 2});
  TriangleMesh liver;
  liver.vertices.resize(4, 3);
  liver.vertices << -0.01, -0.01, 0.009, 0.0523, -0.01, 0.009, -0.01, 0.0517, 0.009, 0.0523, 0.0517, 0.009;
  liver.triangles.resize(2, 3);
  liver.triangles << 0, 2, 1, 1, 2, 3;
  const ConnectiveTissue tissue = CreateConnectiveTissue(liver, gb, {{0, 0, 1}, 5e-3});
  const Vertices gv = Vertices::Zero(gb.num_vertices(), 3);
  const Vertices lv = Vertices::Zero(liver.num_vertices(), 3);
  for (auto _ : state) benchmark::DoNotOptimize(ComputeTissueForces(tissue, gb, gv, liver, lv, {}));
  state.counters["springs"] = tissue.num_alive();
}
BENCHMARK(BM_TissueForces)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace vesica::physics
