// BEM liver stages at the paper's node counts (Table 2: 95, 296, 752) and at 1500 and 3000, on a
// liver-sized ellipsoid (0.10 x 0.07 x 0.04 m, MakeEllipsoidSurface) whose x < -0.06 m cap is the
// fixed region. Names carry stage / nodes / contacts:
//   BM_BemPrecompute/N           surface check + H,G assembly + LU + Green's functions (no cache)
//   BM_BemAssemble/N             H and G only;   BM_BemGreensSolve/N  LU of A0 + Xi = A0^-1 G_free
//     BM_BemCacheLoad/N   reading a valid cache
//   BM_BemCapacitanceFactor/N/s  new contact set: form and factor the 3s x 3s capacitance matrix
//   BM_BemDeform/N/s             global deformation (eq. 4): every node's displacement/traction
//   BM_BemContactForces/N/s      haptic query: contact forces only, O(s^2)
// Times are wall clock ("Time" column); precompute uses both cores (assembly threads, OpenBLAS).
// The Green's functions of each N are cached in $TMPDIR for the run-time benchmarks.

#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>
#include <memory>
#include <numeric>
#include <random>

#include "physics/bem/bem_model.h"
#include "physics/bem/capacitance_solver.h"
#include "physics/bem/dense_lu_solve.h"
#include "physics/bem/ellipsoid_surface.h"

namespace vesica::physics {
namespace {

TriangleMesh LiverLikeEllipsoid(int num_vertices) {
  TriangleMesh mesh = MakeEllipsoidSurface({0.10, 0.07, 0.04}, num_vertices);
  for (int i = 0; i < mesh.num_vertices(); ++i)
    mesh.vertex_labels(i) = mesh.vertices(i, 0) < -0.06 ? kLabelFixed : kLabelNone;
  return mesh;
}

std::string CachePath(int n) {
  return (std::filesystem::temp_directory_path() / ("vesica_bem_bench_" + std::to_string(n) + ".bin")).string();
}

const BemModel& CachedModel(int n) {
  static std::map<int, std::unique_ptr<BemModel>> models;
  auto& model = models[n];
  if (!model) {
    BemPrecomputeOptions options;
    options.cache_path = CachePath(n);
    model = std::make_unique<BemModel>(
        PrecomputeBemModel(LiverLikeEllipsoid(n), LiverMaterial(), "bench ellipsoid", options));
  }
  return *model;
}

// The s free nodes nearest the tip opposite the fixed cap: an instrument's contact patch.
std::vector<int> ContactPatch(const BemModel& model, int s) {
  const Vertices& v = model.rest_surface.vertices;
  int tip = 0;
  v.col(0).maxCoeff(&tip);
  std::vector<int> nodes = model.layout.free_nodes;
  std::partial_sort(nodes.begin(), nodes.begin() + s, nodes.end(), [&](int a, int b) {
    return (v.row(a) - v.row(tip)).squaredNorm() < (v.row(b) - v.row(tip)).squaredNorm();
  });
  nodes.resize(static_cast<std::size_t>(s));
  return nodes;
}

Vertices ContactDisplacements(int s) {
  Vertices u(s, 3);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> d(-2e-3, 2e-3);
  return u.unaryExpr([&](double) { return d(rng); });
}

void SetMemoryCounters(benchmark::State& state, const BemModel& model) {
  state.counters["greens_MiB"] = double(model.greens.size() * sizeof(double)) / (1 << 20);
  state.counters["nodes"] = model.num_nodes();
}

void BM_BemPrecompute(benchmark::State& state) {
  const TriangleMesh mesh = LiverLikeEllipsoid(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    BemModel model = PrecomputeBemModel(mesh, LiverMaterial(), "bench ellipsoid");
    benchmark::DoNotOptimize(model.greens.data());
    state.PauseTiming();
    SetMemoryCounters(state, model);
    state.ResumeTiming();
  }
  state.SetLabel(DenseLinearAlgebraBackend());
}

void BM_BemAssemble(benchmark::State& state) {
  const TriangleMesh mesh = LiverLikeEllipsoid(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    BemMatrices m = AssembleBemMatrices(mesh, LiverMaterial());
    benchmark::DoNotOptimize(m.H.data());
  }
}

void BM_BemGreensSolve(benchmark::State& state) {
  const TriangleMesh mesh = LiverLikeEllipsoid(static_cast<int>(state.range(0)));
  const BemNodeLayout layout = MakeBemNodeLayout(mesh, "bench ellipsoid");
  const BemMatrices matrices = AssembleBemMatrices(mesh, LiverMaterial());
  for (auto _ : state) {
    state.PauseTiming();
    BemMatrices copy = matrices;
    state.ResumeTiming();
    Eigen::MatrixXd greens = ComputeGreensFunctions(std::move(copy), layout);
    benchmark::DoNotOptimize(greens.data());
  }
  state.SetLabel(DenseLinearAlgebraBackend());
}

void BM_BemCacheLoad(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  CachedModel(n);  // makes sure the file exists
  const TriangleMesh mesh = LiverLikeEllipsoid(n);
  BemPrecomputeOptions options;
  options.cache_path = CachePath(n);
  for (auto _ : state) {
    GreensCacheStatus status{};
    BemModel model = PrecomputeBemModel(mesh, LiverMaterial(), "bench ellipsoid", options, &status);
    if (status != GreensCacheStatus::kLoaded) state.SkipWithError("cache not loaded");
    benchmark::DoNotOptimize(model.greens.data());
  }
}

void BM_BemCapacitanceFactor(benchmark::State& state) {
  const BemModel& model = CachedModel(static_cast<int>(state.range(0)));
  const std::vector<int> contacts = ContactPatch(model, static_cast<int>(state.range(1)));
  BemCapacitanceSolver solver(model);
  for (auto _ : state) {
    solver.SetContactNodes(contacts);
    benchmark::ClobberMemory();
  }
  SetMemoryCounters(state, model);
}

void BM_BemDeform(benchmark::State& state) {
  const BemModel& model = CachedModel(static_cast<int>(state.range(0)));
  const int s = static_cast<int>(state.range(1));
  BemCapacitanceSolver solver(model);
  solver.SetContactNodes(ContactPatch(model, s));
  const Vertices u_c = ContactDisplacements(s);
  BemSolution solution;
  for (auto _ : state) {
    solver.Solve(u_c, solution);
    benchmark::DoNotOptimize(solution.displacement_m.data());
  }
}

void BM_BemContactForces(benchmark::State& state) {
  const BemModel& model = CachedModel(static_cast<int>(state.range(0)));
  const int s = static_cast<int>(state.range(1));
  BemCapacitanceSolver solver(model);
  solver.SetContactNodes(ContactPatch(model, s));
  const Vertices u_c = ContactDisplacements(s);
  Vertices forces;
  for (auto _ : state) {
    solver.ContactForces(u_c, forces);
    benchmark::DoNotOptimize(forces.data());
  }
}

void NodeCounts(benchmark::internal::Benchmark* b) {
  for (int n : {95, 296, 752, 1500, 3000}) b->Arg(n);
}
void NodeAndContactCounts(benchmark::internal::Benchmark* b) {
  for (int n : {95, 296, 752, 1500, 3000})
    for (int s : {1, 5, 10, 20}) b->Args({n, s});
}

BENCHMARK(BM_BemPrecompute)->Apply(NodeCounts)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BemAssemble)->Apply(NodeCounts)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BemGreensSolve)->Apply(NodeCounts)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BemCacheLoad)->Apply(NodeCounts)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BemCapacitanceFactor)->Apply(NodeAndContactCounts)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BemDeform)->Apply(NodeAndContactCounts)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BemContactForces)->Apply(NodeAndContactCounts)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace vesica::physics
