// Issue 37's liver study as a benchmark (tools/convergence/liver_hook_study.h): the hook's tip on
// the trainer's liver at refinement level L (0 = the trainer's 1,001 vertices; L passes of graded
// 1:4 splitting toward the tip), with the errors against the CalculiX reference as counters:
//   BM_LiverHookPrecompute/L/B   (B = 1: graded toward the whole bed, not the tip) H, G, LU and Green's functions (no
//   cache); counters: vertices,
//                                force_err, displ_err (relative), contact nodes
//   BM_LiverHookContactForces/L  the haptic query, O(s^2)    (budget 20 us)
//   BM_LiverHookDeform/L         every node's displacement, O(n s)  (budget 0.1 ms)
// and the same with the footprint as traction modes (issue 37's fix; uniform + punch, m = 6):
//   BM_LiverHookModesSetFootprint/L  the modes' loads and compliance, once per contact (footprint)
//   BM_LiverHookModesContactForce/L  the haptic query, O(m^2)   (budget 20 us)
//   BM_LiverHookModesDeform/L        every node's displacement, O(n m)  (budget 0.1 ms)
//   BM_SceneHookContactLoad/R        the scene's row: a disc of R um radius on the trainer's liver
//                                    (MakeToolContactLoad + its compliance), once per step
// Run: build/<dir>/bench/bem/liver_convergence_bench (docs/fidelity.md quotes it).

#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "physics/bem/capacitance_solver.h"
#include "physics/bem/footprint_contact_solver.h"
#include "physics/bem/tool_contact_load.h"
#include "tools/convergence/liver_hook_study.h"

namespace vesica::convergence {
namespace {

struct Level {
  LiverHookSetup setup;
  std::unique_ptr<physics::BemModel> model;
};

const physics::TriangleMesh& Liver() {
  static const physics::TriangleMesh liver = ReadTrainerLiver(VESICA_SOURCE_DIR);
  return liver;
}
const ToolLoadReference& Reference() {
  static const ToolLoadReference ref = ReadLiverHookReference(VESICA_SOURCE_DIR);
  return ref;
}

Level& LevelModel(int levels) {
  static std::map<int, Level> cache;
  Level& l = cache[levels];
  if (!l.model) {
    l.setup = MakeLiverHookSetup(Liver(), Reference(), levels);
    l.model = std::make_unique<physics::BemModel>(
        physics::PrecomputeBemModel(l.setup.surface, physics::LiverMaterial(), "study liver"));
  }
  return l;
}

void BM_LiverHookPrecompute(benchmark::State& state) {
  const LiverHookSetup setup = MakeLiverHookSetup(Liver(), Reference(), static_cast<int>(state.range(0)),
                                                  state.range(1) ? LiverGrading::kTowardBed : LiverGrading::kTowardTip);
  LiverHookResult result;
  for (auto _ : state) result = SolveLiverHook(Liver(), Reference(), setup);
  state.counters["vertices"] = result.vertices;
  state.counters["contact_nodes"] = static_cast<double>(setup.contact.size());
  state.counters["force_err"] = result.force_error;
  state.counters["displ_err"] = result.displacement_error;
}

void BM_LiverHookContactForces(benchmark::State& state) {
  Level& l = LevelModel(static_cast<int>(state.range(0)));
  physics::BemCapacitanceSolver solver(*l.model);
  solver.SetContactNodes(l.setup.contact);
  const physics::Vertices u =
      Reference().prescribed_m.transpose().replicate(static_cast<Eigen::Index>(l.setup.contact.size()), 1);
  physics::Vertices forces;
  for (auto _ : state) {
    solver.ContactForces(u, forces);
    benchmark::DoNotOptimize(forces.data());
  }
  state.counters["contact_nodes"] = static_cast<double>(l.setup.contact.size());
}

void BM_LiverHookDeform(benchmark::State& state) {
  Level& l = LevelModel(static_cast<int>(state.range(0)));
  physics::BemCapacitanceSolver solver(*l.model);
  solver.SetContactNodes(l.setup.contact);
  const physics::Vertices u =
      Reference().prescribed_m.transpose().replicate(static_cast<Eigen::Index>(l.setup.contact.size()), 1);
  physics::BemSolution solution;
  for (auto _ : state) {
    solver.Solve(u, solution);
    benchmark::DoNotOptimize(solution.displacement_m.data());
  }
  state.counters["vertices"] = l.model->num_nodes();
}

void BM_LiverHookModesSetFootprint(benchmark::State& state) {
  Level& l = LevelModel(static_cast<int>(state.range(0)));
  const physics::ToolFootprint footprint = OneRingFootprint(Liver(), l.setup);
  physics::BemFootprintSolver solver(*l.model);
  for (auto _ : state) {
    solver.SetFootprint(physics::MakeFootprintModes(l.setup.surface, l.model->lumped_area_m2, footprint));
    benchmark::DoNotOptimize(solver.mode_compliance().data());
  }
  state.counters["loaded_nodes"] = static_cast<double>(solver.footprint().nodes.size());
}

void BM_LiverHookModesContactForce(benchmark::State& state) {
  Level& l = LevelModel(static_cast<int>(state.range(0)));
  physics::BemFootprintSolver solver(*l.model);
  solver.SetFootprint(
      physics::MakeFootprintModes(l.setup.surface, l.model->lumped_area_m2, OneRingFootprint(Liver(), l.setup)));
  Eigen::Vector3d force;
  for (auto _ : state) {
    force = solver.ContactForce(Reference().prescribed_m);
    benchmark::DoNotOptimize(force.data());
  }
  state.counters["modes"] = solver.footprint().num_modes();
  state.counters["force_err"] = (force - Reference().force_N).norm() / Reference().force_N.norm();
}

void BM_LiverHookModesDeform(benchmark::State& state) {
  Level& l = LevelModel(static_cast<int>(state.range(0)));
  physics::BemFootprintSolver solver(*l.model);
  solver.SetFootprint(
      physics::MakeFootprintModes(l.setup.surface, l.model->lumped_area_m2, OneRingFootprint(Liver(), l.setup)));
  physics::BemSolution solution;
  for (auto _ : state) {
    solver.Solve(Reference().prescribed_m, solution);
    benchmark::DoNotOptimize(solution.displacement_m.data());
  }
  state.counters["vertices"] = l.model->num_nodes();
}

void BM_SceneHookContactLoad(benchmark::State& state) {
  Level& l = LevelModel(0);
  const double radius_m = 1e-6 * static_cast<double>(state.range(0));
  const int triangle = l.setup.footprint_triangles.front();
  const Eigen::Vector3d weights(0.3, 0.3, 0.4);
  const Eigen::Vector3d normal = OneRingFootprint(Liver(), l.setup).normal_W;
  std::size_t nodes = 0;
  for (auto _ : state) {
    const physics::BemContactLoad load = physics::MakeToolContactLoad(*l.model, triangle, weights, normal, radius_m);
    const Eigen::Matrix3d c = physics::ContactLoadCompliance(*l.model, load, load);
    benchmark::DoNotOptimize(c.data());
    nodes = load.nodes.size();
  }
  state.counters["loaded_nodes"] = static_cast<double>(nodes);
}

BENCHMARK(BM_LiverHookPrecompute)
    ->Args({0, 0})
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({1, 1})
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->MeasureProcessCPUTime();  // the assembly runs a thread per core: count them all
BENCHMARK(BM_LiverHookContactForces)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LiverHookDeform)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LiverHookModesSetFootprint)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LiverHookModesContactForce)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_LiverHookModesDeform)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SceneHookContactLoad)->Arg(1500)->Arg(5000)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace vesica::convergence
