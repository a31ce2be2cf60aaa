// Issue 37's gallbladder study as a benchmark (tools/convergence/gallbladder_grasp_study.h): the
// jaw pulled or pressed 5 mm on the committed N-node gallbladders by linear statics, with the
// force error against the CalculiX reference as a counter.
//   BM_GallbladderGrasp/N/<jaw model>/<load>   build + solve; jaw model 0: the nodes inside the
//     jaw prescribed, 1: the footprint's mean (physics/fem/jaw_footprint.h), 2: its mean and tilt;
//     load 0: pull, 1: press. Counters: force_err (relative), jaw_nodes, force_N.
//   BM_GallbladderGrasp/N/<jaw model>/<load>/<element>: as above on element 0: linear tets, 1: the
//     average-nodal-pressure tet, 2: 10-node tets (jaw model 3: the rectangle's 4 x 2 cells).
//   BM_ElementStepCost/N/<element>: what the candidates would cost the trainer's step, which is a
//     rotated-factor PCG (physics/fem): per iteration one product with K and one solve with the
//     rest factor. Timed: that pair, on the bed-held K of the N-node mesh. Counters: dofs, nnz_K,
//     nnz_L (the factor's), the two's cost scales the step's PCG part.
//   BM_JawSubgridCompliance/N/<patch radius mm>: what the scene computes once per grasp
//     (physics/fem/jaw_subgrid_compliance.h) for the reference's jaw on the N-node mesh: the linear
//     and 10-node patches' jaw compliances. Counters: patch_tets, patch_dofs.
// Run: build/<dir>/bench/fem/gallbladder_convergence_bench (docs/fidelity.md quotes it).

#include <benchmark/benchmark.h>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "physics/fem/small_strain_stiffness.h"
#include "physics/mesh/mesh_topology.h"
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
  const auto formulation = static_cast<TetFormulation>(state.range(3));
  for (auto _ : state) result = SolveGallbladderGrasp(mesh, liver, ref, model, load, formulation);
  state.SetLabel(std::string(JawModelName(model)) + ", " + TetFormulationName(formulation));
  state.counters["force_err"] = result.force_error;
  state.counters["force_N"] = result.force_N.norm();
  state.counters["jaw_nodes"] = result.jaw_nodes;
}
BENCHMARK(BM_GallbladderGrasp)
    ->ArgsProduct({{300, 600, 1000, 1600, 3000}, {0, 1, 2}, {0, 1}, {0}})
    ->ArgsProduct({{300, 600, 1000, 1600, 3000}, {1, 3}, {0, 1}, {1, 2}})
    ->Unit(benchmark::kMillisecond);

void BM_JawSubgridCompliance(benchmark::State& state) {
  const ToolLoadReference ref = ReadGallbladderGraspReference(VESICA_SOURCE_DIR);
  const physics::TetrahedralMesh mesh = ReadTrainerGallbladder(VESICA_SOURCE_DIR, static_cast<int>(state.range(0)));
  const physics::TetBoundary boundary = physics::ExtractBoundary(mesh);
  physics::RectangularFootprint jaw;
  jaw.centre_m = ref.centre_m;
  jaw.normal = ref.prescribed_m.normalized();
  jaw.long_axis = (ref.jaw_long_axis - ref.jaw_long_axis.dot(jaw.normal) * jaw.normal).normalized();
  physics::JawSubgridSettings settings;
  settings.patch_radius_m = 1e-3 * static_cast<double>(state.range(1));
  physics::JawSubgridCompliance c;
  for (auto _ : state)
    c = physics::ComputeJawSubgridCompliance(mesh, boundary, physics::ElasticMaterial{2300.0, 0.45, 1000.0}, jaw,
                                             settings);
  state.counters["patch_tets"] = c.patch_tets;
  state.counters["patch_dofs"] = c.patch_dofs;
}
BENCHMARK(BM_JawSubgridCompliance)->ArgsProduct({{1000}, {10, 15, 20}})->Unit(benchmark::kMillisecond);

void BM_ElementStepCost(benchmark::State& state) {
  const physics::TetrahedralMesh mesh = ReadTrainerGallbladder(VESICA_SOURCE_DIR, static_cast<int>(state.range(0)));
  const physics::TriangleMesh liver = ReadTrainerLiver(VESICA_SOURCE_DIR);
  const physics::ElasticMaterial material{2300.0, 0.45, 1000.0};
  const auto formulation = static_cast<TetFormulation>(state.range(1));
  const physics::QuadraticTetMesh tet10 = physics::MakeQuadraticTetMesh(mesh);
  const Eigen::SparseMatrix<double> k =
      formulation == TetFormulation::kLinear      ? physics::LinearTetStiffness(mesh, material)
      : formulation == TetFormulation::kQuadratic ? physics::QuadraticTetStiffness(tet10, material)
                                                  : physics::NodalPressureTetStiffness(mesh, material);
  // The bed held as in the study (its midpoints too: the step's cost hardly depends on which).
  const physics::TetBoundary boundary = physics::ExtractBoundary(mesh);
  std::vector<bool> held(static_cast<size_t>(k.rows() / 3), false);
  for (int s = 0; s < boundary.surface.num_vertices(); ++s)
    if ((liver.vertices.rowwise() - boundary.surface.vertices.row(s)).rowwise().norm().minCoeff() < kBedDistance_m)
      held[static_cast<size_t>(boundary.surface_to_volume(s))] = true;
  if (formulation == TetFormulation::kQuadratic)
    for (const auto& [edge, mid] : tet10.edge_midpoints)
      held[static_cast<size_t>(mid)] = held[static_cast<size_t>(edge.first)] && held[static_cast<size_t>(edge.second)];
  std::vector<int> index(static_cast<size_t>(k.rows()), -1);
  int n = 0;
  for (Eigen::Index i = 0; i < k.rows(); ++i)
    if (!held[static_cast<size_t>(i / 3)]) index[static_cast<size_t>(i)] = n++;
  std::vector<Eigen::Triplet<double>> kept;
  for (int col = 0; col < k.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator e(k, col); e; ++e)
      if (index[static_cast<size_t>(e.row())] >= 0 && index[static_cast<size_t>(e.col())] >= 0)
        kept.emplace_back(index[static_cast<size_t>(e.row())], index[static_cast<size_t>(e.col())], e.value());
  Eigen::SparseMatrix<double> k_ff(n, n);
  k_ff.setFromTriplets(kept.begin(), kept.end());
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> factor(k_ff);
  const Eigen::VectorXd x = Eigen::VectorXd::Ones(n);
  Eigen::VectorXd y, z;
  for (auto _ : state) {
    y = k_ff * x;
    z = factor.solve(y);
    benchmark::DoNotOptimize(z.data());
  }
  state.SetLabel(TetFormulationName(formulation));
  state.counters["dofs"] = n;
  state.counters["nnz_K"] = static_cast<double>(k_ff.nonZeros());
  state.counters["nnz_L"] = factor.cholmod().lnz;
}
BENCHMARK(BM_ElementStepCost)->ArgsProduct({{1000, 3000}, {0, 1, 2}})->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace vesica::convergence
