// Ray queries per second and BVH refit time of SurfaceRayCaster on icospheres of 642 and
// 2,562 vertices (about the 1,000- and 3,000-vertex organ surfaces of issue 6).
#include <benchmark/benchmark.h>

#include <cmath>

#include "physics/collision/surface_ray_caster.h"
#include "physics/mesh/primitives.h"

namespace vesica::physics {
namespace {

// levels 3 -> 642 vertices, 4 -> 2,562 vertices.
void BM_FirstHit(benchmark::State& state) {
  const TriangleMesh sphere = MakeIcosphere(0.05, static_cast<int>(state.range(0)));
  SurfaceRayCaster caster;
  caster.AddSurface(sphere);
  int i = 0, hits = 0;
  for (auto _ : state) {
    // Tool segments from outside toward the centre, 4 cm long, sweeping directions.
    const double a = 0.01 * i++, b = 0.007 * i;
    const Eigen::Vector3d dir(std::cos(a) * std::sin(b + 0.3), std::sin(a) * std::sin(b + 0.3), std::cos(b + 0.3));
    const auto hit = caster.FirstHit({0.07 * dir, 0.03 * dir});
    hits += hit.has_value();
    benchmark::DoNotOptimize(hit);
  }
  state.counters["vertices"] = sphere.num_vertices();
  state.counters["hit_fraction"] = static_cast<double>(hits) / static_cast<double>(state.iterations());
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_FirstHit)->Arg(3)->Arg(4);

void BM_Refit(benchmark::State& state) {
  const TriangleMesh sphere = MakeIcosphere(0.05, static_cast<int>(state.range(0)));
  SurfaceRayCaster caster;
  const int id = caster.AddSurface(sphere);
  Vertices moved = sphere.vertices;
  int i = 0;
  for (auto _ : state) {
    moved = sphere.vertices * (1.0 + 0.01 * std::sin(0.1 * i++));  // breathing deformation
    caster.UpdateVertices(id, moved);
  }
  state.counters["vertices"] = sphere.num_vertices();
}
BENCHMARK(BM_Refit)->Arg(3)->Arg(4)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace vesica::physics
