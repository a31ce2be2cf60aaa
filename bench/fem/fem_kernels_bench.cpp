// Breakdown of a corotational step at the Table 3 sizes: element pass (rotations, forces,
// tangent assembly), one sparse matrix-vector product (the cost of one PCG iteration), one
// CHOLMOD solve (the cost of one preconditioner application when the factor preconditions PCG) and
// one Gauss-Seidel sweep of the shipped preconditioner.

#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "physics/fem/cholmod_solver.h"
#include "physics/fem/elastic_forces.h"
#include "physics/fem/pcg_solver.h"
#include "physics/mesh/primitives.h"

namespace vesica::physics {
namespace {

FemModel BoxModel(const Eigen::Vector3i& cells, ElementKernel kernel = ElementKernel::kAuto) {
  FemSettings s;
  s.material = {2300.0, 0.45, 1000.0};
  s.element_kernel = kernel;
  return BuildFemModel(MakeBoxTetMesh({0.08, 0.03, 0.03}, cells), s, {});
}

// A smooth bend-and-twist displacement, so every element has a non-trivial rotation.
Eigen::VectorXd Deformation(const FemModel& m) {
  Eigen::VectorXd u(m.num_dofs());
  for (int i = 0; i < m.num_nodes(); ++i) {
    const double x = m.rest_mesh.vertices(i, 0);
    u.segment<3>(3 * i) = Eigen::Vector3d(0.0, 0.2 * x * x, 0.1 * x);
  }
  return u;
}

void BM_FemElementPass(benchmark::State& state, Eigen::Vector3i cells) {
  const FemModel m = BoxModel(cells);
  const Eigen::VectorXd u = Deformation(m);
  Eigen::VectorXd tangent, force;
  std::vector<Eigen::Vector4d> cache;
  ComputeElasticForces(m, u, &tangent, &force, &cache);  // warm the rotation cache
  for (auto _ : state) benchmark::DoNotOptimize(ComputeElasticForces(m, u, &tangent, &force, &cache));
  state.counters["nodes"] = m.num_nodes();
  state.counters["ns_per_tet"] =
      benchmark::Counter(static_cast<double>(m.rest_mesh.num_tets()) * 1e-9,
                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// The same pass without the tangent: rotations and forces only (separates the assembly cost).
void BM_FemElementForces(benchmark::State& state, Eigen::Vector3i cells) {
  const FemModel m = BoxModel(cells);
  const Eigen::VectorXd u = Deformation(m);
  Eigen::VectorXd force;
  std::vector<Eigen::Vector4d> cache;
  ComputeElasticForces(m, u, nullptr, &force, &cache);
  for (auto _ : state) benchmark::DoNotOptimize(ComputeElasticForces(m, u, nullptr, &force, &cache));
  state.counters["nodes"] = m.num_nodes();
}

// The element pass with a given kernel (scalar reference, AVX2, AVX-512): the rows above run
// kAuto (the widest this CPU has, unless VESICA_FEM_ELEMENT_KERNEL says otherwise).
void BM_FemElementPassKernel(benchmark::State& state, Eigen::Vector3i cells, ElementKernel kernel, bool tangent) {
  const FemModel m = BoxModel(cells, kernel);
  const Eigen::VectorXd u = Deformation(m);
  Eigen::VectorXd k, force;
  std::vector<Eigen::Vector4d> cache;
  ComputeElasticForces(m, u, tangent ? &k : nullptr, &force, &cache);
  for (auto _ : state) benchmark::DoNotOptimize(ComputeElasticForces(m, u, tangent ? &k : nullptr, &force, &cache));
  state.counters["ns_per_tet"] =
      benchmark::Counter(static_cast<double>(m.rest_mesh.num_tets()) * 1e-9,
                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_FemSpmv(benchmark::State& state, Eigen::Vector3i cells) {
  const FemModel m = BoxModel(cells);
  const Eigen::VectorXd x = Deformation(m);
  Eigen::VectorXd y;
  for (auto _ : state) {
    SymmetricPatternMultiply(m.pattern, m.linear_stiffness_values, x, y);
    benchmark::DoNotOptimize(y.data());
  }
  state.counters["nodes"] = m.num_nodes();
  state.counters["nnz"] = static_cast<double>(m.pattern.structure.nonZeros());
}

// The tangent product element by element (CorotationalTangentTimes, kRotatedFactorPcg's
// matrix-free product), against BM_FemSpmv's assembled one.
void BM_FemTangentTimes(benchmark::State& state, Eigen::Vector3i cells) {
  const FemModel m = BoxModel(cells);
  const Eigen::VectorXd u = Deformation(m);
  Eigen::VectorXd force, y;
  std::vector<Eigen::Vector4d> cache;
  HugePageVector<double> turned;  // as FemBody's matrix-free step has them
  ComputeElasticForces(m, u, nullptr, &force, &cache, &turned);
  for (auto _ : state) {
    CorotationalTangentTimes(m, cache, u, y, &turned);
    benchmark::DoNotOptimize(y.data());
  }
  state.counters["ns_per_tet"] =
      benchmark::Counter(static_cast<double>(m.rest_mesh.num_tets()) * 1e-9,
                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_FemCholmodSolve(benchmark::State& state, Eigen::Vector3i cells) {
  const FemModel m = BoxModel(cells);
  Eigen::VectorXd s = m.linear_stiffness_values;
  for (int i = 0; i < m.num_dofs(); ++i) s[m.pattern.diagonal_slot[i]] += 1e4 * m.lumped_mass_kg[i];  // M/h^2 + K
  CholmodSolver cholesky;
  cholesky.Factorize(m.pattern, s);
  const Eigen::VectorXd b = Deformation(m);
  Eigen::VectorXd x;
  for (auto _ : state) {
    cholesky.Solve(b, x);
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["nodes"] = m.num_nodes();
}

// The same solve with L rounded to float (CholmodSolver::SolveSinglePrecision, the
// kRotatedFactorPcg preconditioner).
void BM_FemCholmodSolveSingle(benchmark::State& state, Eigen::Vector3i cells) {
  const FemModel m = BoxModel(cells);
  Eigen::VectorXd s = m.linear_stiffness_values;
  for (int i = 0; i < m.num_dofs(); ++i) s[m.pattern.diagonal_slot[i]] += 1e4 * m.lumped_mass_kg[i];
  CholmodSolver cholesky;
  cholesky.Factorize(m.pattern, s, true);
  const Eigen::VectorXd b = Deformation(m);
  Eigen::VectorXd x;
  for (auto _ : state) {
    cholesky.SolveSinglePrecision(b, x);
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["nodes"] = m.num_nodes();
}

// The same solve with L stored as IEEE half times a power of two, solved in float (the
// kRotatedFactorPcg default on CPUs with F16C; falls back to the float copy without it).
void BM_FemCholmodSolveHalf(benchmark::State& state, Eigen::Vector3i cells) {
  const FemModel m = BoxModel(cells);
  Eigen::VectorXd s = m.linear_stiffness_values;
  for (int i = 0; i < m.num_dofs(); ++i) s[m.pattern.diagonal_slot[i]] += 1e4 * m.lumped_mass_kg[i];
  CholmodSolver cholesky;
  cholesky.Factorize(m.pattern, s, true, true);
  const Eigen::VectorXd b = Deformation(m);
  Eigen::VectorXd x;
  for (auto _ : state) {
    cholesky.SolveSinglePrecision(b, x);
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["nodes"] = m.num_nodes();
  state.counters["half"] = cholesky.half_storage() ? 1.0 : 0.0;
  state.counters["factor_MB"] = static_cast<double>(cholesky.low_precision_bytes()) * 1e-6;
}

// One backward block Gauss-Seidel sweep on the float rows of M/h^2 + K (the shipped
// preconditioner's sweeps), with its data in cache or, `evict`, after streaming 8 MB through the
// caches as the half solve between the two sweeps of a preconditioner application does (the
// eviction is not timed).
void BM_FemGaussSeidelSweep(benchmark::State& state, Eigen::Vector3i cells, bool evict) {
  if (!FloatBlockRows::available()) {
    state.SkipWithError("no AVX2 + FMA");
    return;
  }
  const FemModel m = BoxModel(cells);
  Eigen::VectorXd s = m.linear_stiffness_values;
  for (int i = 0; i < m.num_dofs(); ++i) s[m.pattern.diagonal_slot[i]] += 1e4 * m.lumped_mass_kg[i];
  FloatBlockRows rows;
  rows.Update(m.pattern, s);
  BlockJacobiPreconditioner jacobi;
  jacobi.Compute(rows);
  const Eigen::VectorXd b = Deformation(m);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
  std::vector<double> other(evict ? 1 << 20 : 0, 1.0);
  for (auto _ : state) {
    if (evict) {
      state.PauseTiming();
      double sum = 0.0;
      for (double& v : other) sum += (v += 1e-9);
      benchmark::DoNotOptimize(sum);
      state.ResumeTiming();
    }
    BlockGaussSeidelSweep(rows, jacobi.inverse_blocks(), b, x, false);
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["blocks"] = static_cast<double>(m.pattern.structure.nonZeros() / 9);
}

const bool kRegistered = [] {
  // The grids fem_step_bench.cpp uses for Table 3's end points: 310 -> 300 nodes, 2,865 -> 2,900.
  const std::pair<Eigen::Vector3i, const char*> sizes[] = {{{11, 4, 4}, "310"}, {{28, 9, 9}, "2865"}};
  for (const auto& [cells, name] : sizes) {
    benchmark::RegisterBenchmark((std::string("BM_FemElementPass/corotational/") + name).c_str(), BM_FemElementPass,
                                 cells)
        ->Unit(benchmark::kMillisecond)
        ->MinTime(0.2);
    benchmark::RegisterBenchmark((std::string("BM_FemElementForces/corotational/") + name).c_str(), BM_FemElementForces,
                                 cells)
        ->Unit(benchmark::kMillisecond)
        ->MinTime(0.2);
    const std::pair<ElementKernel, const char*> kernels[] = {
        {ElementKernel::kScalar, "scalar"}, {ElementKernel::kAvx2, "avx2"}, {ElementKernel::kAvx512, "avx512"}};
    for (const auto& [kernel, kernel_name] : kernels) {
      if (ResolveElementKernel(kernel) != kernel) continue;  // not on this CPU
      for (bool tangent : {true, false})
        benchmark::RegisterBenchmark(
            (std::string(tangent ? "BM_FemElementPass/corotational/" : "BM_FemElementForces/corotational/") + name +
             "/" + kernel_name)
                .c_str(),
            BM_FemElementPassKernel, cells, kernel, tangent)
            ->Unit(benchmark::kMillisecond)
            ->MinTime(0.2);
    }
    benchmark::RegisterBenchmark((std::string("BM_FemSpmv/") + name).c_str(), BM_FemSpmv, cells)
        ->Unit(benchmark::kMillisecond)
        ->MinTime(0.2);
    for (bool evict : {false, true})
      benchmark::RegisterBenchmark(
          (std::string("BM_FemGaussSeidelSweep/") + name + (evict ? "/after_eviction" : "/in_cache")).c_str(),
          BM_FemGaussSeidelSweep, cells, evict)
          ->Unit(benchmark::kMillisecond)
          ->MinTime(0.2);
    benchmark::RegisterBenchmark((std::string("BM_FemTangentTimes/") + name).c_str(), BM_FemTangentTimes, cells)
        ->Unit(benchmark::kMillisecond)
        ->MinTime(0.2);
    benchmark::RegisterBenchmark((std::string("BM_FemCholmodSolve/") + name).c_str(), BM_FemCholmodSolve, cells)
        ->Unit(benchmark::kMillisecond)
        ->MinTime(0.2);
    benchmark::RegisterBenchmark((std::string("BM_FemCholmodSolveSingle/") + name).c_str(), BM_FemCholmodSolveSingle,
                                 cells)
        ->Unit(benchmark::kMillisecond)
        ->MinTime(0.2);
    benchmark::RegisterBenchmark((std::string("BM_FemCholmodSolveHalf/") + name).c_str(), BM_FemCholmodSolveHalf, cells)
        ->Unit(benchmark::kMillisecond)
        ->MinTime(0.2);
  }
  return true;
}();

}  // namespace
}  // namespace vesica::physics
