// Issue 37's gallbladder study as a benchmark (tools/convergence/gallbladder_grasp_study.h): the
// jaw pulled 5 mm on the committed N-node gallbladders by linear statics, with the force error
// against the CalculiX reference as a counter.
//   BM_GallbladderGrasp/N   build + solve; counters: force_err (relative), jaw_nodes, force_N
// Run: build/<dir>/bench/fem/gallbladder_convergence_bench (docs/fidelity.md quotes it).

#include <benchmark/benchmark.h>

#include "tools/convergence/gallbladder_grasp_study.h"
#include "tools/convergence/liver_hook_study.h"

namespace vesica::convergence {
namespace {

void BM_GallbladderGrasp(benchmark::State& state) {
  const physics::TriangleMesh liver = ReadTrainerLiver(VESICA_SOURCE_DIR);
  const ToolLoadReference ref = ReadGallbladderGraspReference(VESICA_SOURCE_DIR);
  const physics::TetrahedralMesh mesh = ReadTrainerGallbladder(VESICA_SOURCE_DIR, static_cast<int>(state.range(0)));
  GallbladderGraspResult result;
  for (auto _ : state) result = SolveGallbladderGrasp(mesh, liver, ref);
  state.counters["force_err"] = result.force_error;
  state.counters["force_N"] = result.force_N.norm();
  state.counters["jaw_nodes"] = result.jaw_nodes;
}
BENCHMARK(BM_GallbladderGrasp)->Arg(300)->Arg(600)->Arg(1000)->Arg(1600)->Arg(3000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace vesica::convergence
