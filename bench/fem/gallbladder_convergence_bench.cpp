// Issue 37's gallbladder study as a benchmark (tools/convergence/gallbladder_grasp_study.h): the
// jaw pulled or pressed 5 mm on the committed N-node gallbladders by linear statics, with the
// force error against the CalculiX reference as a counter.
//   BM_GallbladderGrasp/N/<jaw model>/<load>   build + solve; jaw model 0: the nodes inside the
//     jaw prescribed, 1: the footprint's mean (physics/fem/jaw_footprint.h), 2: its mean and tilt;
//     load 0: pull, 1: press. Counters: force_err (relative), jaw_nodes, force_N.
// Run: build/<dir>/bench/fem/gallbladder_convergence_bench (docs/fidelity.md quotes it).

#include <benchmark/benchmark.h>

#include "tools/convergence/gallbladder_grasp_study.h"
#include "tools/convergence/liver_hook_study.h"

namespace vesica::convergence {
namespace {

void BM_GallbladderGrasp(benchmark::State& state) {
  const auto model = static_cast<JawModel>(state.range(1));
  const JawLoad load = state.range(2) == 0 ? JawLoad::kPull : JawLoad::kPress;
  const physics::TriangleMesh liver = ReadTrainerLiver(VESICA_SOURCE_DIR);
  const ToolLoadReference ref = load == JawLoad::kPull ? ReadGallbladderGraspReference(VESICA_SOURCE_DIR)
                                                       : ReadGallbladderPressReference(VESICA_SOURCE_DIR);
  const physics::TetrahedralMesh mesh = ReadTrainerGallbladder(VESICA_SOURCE_DIR, static_cast<int>(state.range(0)));
  GallbladderGraspResult result;
  for (auto _ : state) result = SolveGallbladderGrasp(mesh, liver, ref, model, load);
  state.SetLabel(JawModelName(model));
  state.counters["force_err"] = result.force_error;
  state.counters["force_N"] = result.force_N.norm();
  state.counters["jaw_nodes"] = result.jaw_nodes;
}
BENCHMARK(BM_GallbladderGrasp)
    ->ArgsProduct({{300, 600, 1000, 1600, 3000}, {0, 1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace vesica::convergence
