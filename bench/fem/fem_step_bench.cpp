// Per-step time of a FEM gallbladder body at the node counts of the gallbladder paper's Table 3,
// and the pre-process (model build + first factorisation). The paper's mesh is a pear-shaped
// gallbladder; here a box of gallbladder size (8 x 3 x 3 cm) whose grid gives a node count close
// to each Table 3 entry (the counter `nodes` says which). Newmark (the paper's integrator),
// gallbladder material (2.3 kPa, nu 0.45), one face fixed, a sinusoidal pull at the free end so
// every step has work to do (a body at rest would let the warm-started PCG stop at once).

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <string>

#include "bench/fem/min_statistic.h"
#include "bench/fem/pulled_body_steps.h"
#include "physics/fem/fem_body.h"
#include "physics/mesh/primitives.h"

namespace vesica::physics {
namespace {

constexpr int kTable3Nodes[] = {310, 380, 469, 597, 769, 979, 1272, 1580, 1980, 2401, 2865};

// Cells (n, m, m) of an 8 x 3 x 3 cm box whose node count is closest to `nodes`.
Eigen::Vector3i CellsForNodes(int nodes) {
  Eigen::Vector3i best(1, 1, 1);
  int best_error = 1 << 30;
  for (int m = 1; m < 30; ++m)
    for (int n = 2 * m; n <= 3 * m + 1; ++n) {
      const int error = std::abs((n + 1) * (m + 1) * (m + 1) - nodes);
      if (error < best_error) best_error = error, best = {n, m, m};
    }
  return best;
}

std::shared_ptr<FemModel> GallbladderModel(int nodes, ElementModel element, LinearSolverKind solver,
                                           int refresh_steps = 1, int max_iterations = 20, bool gauss_seidel = false,
                                           int sweeps = 0, double local_share = -1.0) {
  const TetrahedralMesh mesh = MakeBoxTetMesh({0.08, 0.03, 0.03}, CellsForNodes(nodes));
  FemSettings s = PulledGallbladderSettings("gallbladder box", element, solver, max_iterations, gauss_seidel);
  s.cholmod_refresh_steps = refresh_steps;
  if (sweeps > 0) s.rotated_factor_sweeps = sweeps;                    // 0: the default
  if (local_share >= 0.0) s.rotated_factor_local_share = local_share;  // negative: the default
  std::vector<DirichletNode> fixed;
  for (int i = 0; i < mesh.num_vertices(); ++i)
    if (mesh.vertices(i, 0) < 1e-12) fixed.push_back({i, {true, true, true}});
  return std::make_shared<FemModel>(BuildFemModel(mesh, s, fixed));
}

void BM_FemStep(benchmark::State& state, ElementModel element, LinearSolverKind solver, int nodes, int refresh_steps,
                int max_iterations, bool gauss_seidel, int sweeps, double local_share) {
  const auto model =
      GallbladderModel(nodes, element, solver, refresh_steps, max_iterations, gauss_seidel, sweeps, local_share);
  RunPulledSteps(state, model, {{model->num_nodes() - 1}, 0.05, Eigen::Vector3d(0.3, 0.0, 1.0)});
}

// The step stopped early, by a looser tolerance or an iteration cap, beside the shipped converged
// one: what a time budget below the converged step's would cost in accuracy (the counter
// max_dev_from_converged_um: the farthest any node strays from the 1e-8 run over the 40 steps).
// The paper's own solver (block-Jacobi PCG, 1e-8, at most 20 iterations) gets the same counter.
void BM_FemStepLoose(benchmark::State& state, int nodes, LinearSolverKind solver, bool gauss_seidel, double tolerance,
                     int max_iterations) {
  const auto converged =
      GallbladderModel(nodes, ElementModel::kCorotational, LinearSolverKind::kRotatedFactorPcg, 1, 100, true);
  const SinusoidalPull pull{{converged->num_nodes() - 1}, 0.05, Eigen::Vector3d(0.3, 0.0, 1.0)};
  const auto reference = PulledTrajectory(converged, pull, 1 + static_cast<int>(state.max_iterations));
  const auto loose =
      solver == LinearSolverKind::kRotatedFactorPcg && gauss_seidel
          ? std::make_shared<FemModel>(*converged)
          : GallbladderModel(nodes, ElementModel::kCorotational, solver, 1, max_iterations, gauss_seidel);
  loose->settings.pcg_relative_tolerance = tolerance;
  loose->settings.pcg_max_iterations = max_iterations;
  RunPulledSteps(state, loose, pull, &reference);
}

// The model, the first assembly and factorisation: with kCholmod the exact factor, with
// kRotatedFactorPcg the rest factor and its half-precision partitioned inverse (and one step).
void BM_FemPreprocess(benchmark::State& state, int nodes, LinearSolverKind solver, bool gauss_seidel) {
  for (auto _ : state) {
    const auto model = GallbladderModel(nodes, ElementModel::kCorotational, solver, 1, 100, gauss_seidel);
    FemBody body(model);
    benchmark::DoNotOptimize(body.Step().accepted);
  }
}

const bool kRegistered = [] {
  const std::pair<ElementModel, const char*> elements[] = {{ElementModel::kLinear, "linear"},
                                                           {ElementModel::kCorotational, "corotational"}};
  const std::pair<LinearSolverKind, const char*> solvers[] = {{LinearSolverKind::kPcg, "pcg"},
                                                              {LinearSolverKind::kCholmod, "cholmod"}};
  for (const auto& [element, element_name] : elements)
    for (const auto& [solver, solver_name] : solvers)
      for (int nodes : kTable3Nodes) {
        const std::string name =
            std::string("BM_FemStep/") + element_name + "/" + solver_name + "/" + std::to_string(nodes);
        WithMinimum(
            benchmark::RegisterBenchmark(name.c_str(), BM_FemStep, element, solver, nodes, 1, 20, false, 0, -1.0))
            ->Unit(benchmark::kMillisecond)
            ->MinTime(0.2);
      }
  // Converged corotational steps without a factorisation every step: factor every 10th step,
  // PCG (tolerance 1e-8, at most 20 iterations) preconditioned by it in between.
  for (int nodes : {310, 2865})
    benchmark::RegisterBenchmark(("BM_FemStep/corotational/cholmod_refresh10/" + std::to_string(nodes)).c_str(),
                                 BM_FemStep, ElementModel::kCorotational, LinearSolverKind::kCholmod, nodes, 10, 20,
                                 false, 0, -1.0)
        ->Unit(benchmark::kMillisecond)
        ->MinTime(0.5);
  // Converged corotational steps: PCG (tolerance 1e-8, cap 100 so that every step converges)
  // preconditioned by the rest factor turned per node into the current frame
  // (LinearSolverKind::kRotatedFactorPcg), alone or between block Gauss-Seidel sweeps (_gs).
  // (The shipped variant, _gs, at every Table 3 count; the one without sweeps at the ends.)
  for (int nodes : kTable3Nodes)
    for (bool gauss_seidel : {false, true}) {
      if (!gauss_seidel && nodes != 310 && nodes != 2865) continue;
      WithMinimum(benchmark::RegisterBenchmark(("BM_FemStep/corotational/rotated_factor" +
                                                std::string(gauss_seidel ? "_gs/" : "/") + std::to_string(nodes))
                                                   .c_str(),
                                               BM_FemStep, ElementModel::kCorotational,
                                               LinearSolverKind::kRotatedFactorPcg, nodes, 1, 100, gauss_seidel, 0,
                                               -1.0))
          ->Unit(benchmark::kMillisecond)
          ->Iterations(40);  // the same 40 steps from rest for both: later steps need more iterations
    }
  // A bound for every factor-based preconditioner: a linear body's system is its rest system, so
  // this PCG is preconditioned by the half-precision partitioned inverse of the exact factor of the
  // very system it solves: what a corotational step would get from a factorisation of its current
  // tangent that cost nothing. Its iterations (and the half solve's time) are the floor.
  for (int nodes : {310, 2865})
    WithMinimum(benchmark::RegisterBenchmark(("BM_FemStep/linear/rotated_factor/" + std::to_string(nodes)).c_str(),
                                             BM_FemStep, ElementModel::kLinear, LinearSolverKind::kRotatedFactorPcg,
                                             nodes, 1, 100, false, 0, -1.0))
        ->Unit(benchmark::kMillisecond)
        ->Iterations(40);
  // The Gauss-Seidel variant without the exact solve on the nodes whose tets turn most apart
  // (rotated_factor_local_share = 0; the rows above use the default share).
  for (int nodes : {310, 2865})
    WithMinimum(benchmark::RegisterBenchmark(
                    ("BM_FemStep/corotational/rotated_factor_gs_nolocal/" + std::to_string(nodes)).c_str(), BM_FemStep,
                    ElementModel::kCorotational, LinearSolverKind::kRotatedFactorPcg, nodes, 1, 100, true, 0, 0.0))
        ->Unit(benchmark::kMillisecond)
        ->Iterations(40);
  // The Gauss-Seidel variant with 2 and 3 sweeps a side (the rows above: the default, 1): fewer
  // iterations, each dearer.
  for (int sweeps : {2, 3})
    benchmark::RegisterBenchmark(
        ("BM_FemStep/corotational/rotated_factor_gs" + std::to_string(sweeps) + "/2865").c_str(), BM_FemStep,
        ElementModel::kCorotational, LinearSolverKind::kRotatedFactorPcg, 2865, 1, 100, true, sweeps, -1.0)
        ->Unit(benchmark::kMillisecond)
        ->Iterations(40);
  // Early stops (the shipped solver; _tol: a looser tolerance, _it: at most that many iterations
  // at 1e-8), each with its distance from the converged run; _tol1e-8 is the converged row itself
  // (its deviation: zero, the check); rotated_factor_it1: one iteration without the sweeps (the
  // cheapest step there is: no S at all); pcg_it20: the paper's solver.
  struct Stop {
    const char* name;
    LinearSolverKind solver;
    bool gauss_seidel;
    double tolerance;
    int max_iterations;
  };
  constexpr LinearSolverKind kShipped = LinearSolverKind::kRotatedFactorPcg;
  const Stop stops[] = {{"rotated_factor_gs_tol1e-8", kShipped, true, 1e-8, 100},
                        {"rotated_factor_gs_tol1e-6", kShipped, true, 1e-6, 100},
                        {"rotated_factor_gs_tol1e-4", kShipped, true, 1e-4, 100},
                        {"rotated_factor_gs_tol1e-3", kShipped, true, 1e-3, 100},
                        {"rotated_factor_gs_tol1e-2", kShipped, true, 1e-2, 100},
                        {"rotated_factor_gs_it1", kShipped, true, 1e-8, 1},
                        {"rotated_factor_gs_it2", kShipped, true, 1e-8, 2},
                        {"rotated_factor_gs_it3", kShipped, true, 1e-8, 3},
                        {"rotated_factor_it1", kShipped, false, 1e-8, 1},
                        {"pcg_it20", LinearSolverKind::kPcg, false, 1e-8, 20}};
  for (const Stop& stop : stops)
    WithMinimum(benchmark::RegisterBenchmark(("BM_FemStep/corotational/" + std::string(stop.name) + "/2865").c_str(),
                                             BM_FemStepLoose, 2865, stop.solver, stop.gauss_seidel, stop.tolerance,
                                             stop.max_iterations))
        ->Unit(benchmark::kMillisecond)
        ->Iterations(40);
  for (int nodes : kTable3Nodes)
    benchmark::RegisterBenchmark(("BM_FemPreprocess/" + std::to_string(nodes)).c_str(), BM_FemPreprocess, nodes,
                                 LinearSolverKind::kCholmod, false)
        ->Unit(benchmark::kMillisecond)
        ->MinTime(0.2);
  for (int nodes : kTable3Nodes)
    benchmark::RegisterBenchmark(("BM_FemPreprocess/rotated_factor_gs/" + std::to_string(nodes)).c_str(),
                                 BM_FemPreprocess, nodes, LinearSolverKind::kRotatedFactorPcg, true)
        ->Unit(benchmark::kMillisecond)
        ->MinTime(0.2);
  return true;
}();

}  // namespace
}  // namespace vesica::physics
