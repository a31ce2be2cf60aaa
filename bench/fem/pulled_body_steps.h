#pragma once
// The timed loop of the BM_FemStep rows: a body pulled by a sinusoidal force shared by some of
// its nodes (so every step has work to do: a body at rest would let the warm-started PCG stop at
// once), one untimed first step (the first assembly and factorisation are pre-process), then one
// benchmark iteration a step. Counters: iterations a step, the worst relative residual, rejected
// steps, the preconditioned spectrum's widest range, how far the pulled nodes went and, given a
// converged run of the same pull, how far any node strays from it.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "bench/fem/spectrum_counters.h"
#include "physics/fem/fem_body.h"

namespace vesica::physics {

/// The pulled gallbladder's settings shared by the box rows and the anatomical rows, so both run
/// the same physical problem: gallbladder material (2.3 kPa, nu 0.45), Newmark (the paper's
/// integrator), h = 10 ms, Rayleigh 1 /s and 0.01 s.
inline FemSettings PulledGallbladderSettings(const char* body_name, ElementModel element, LinearSolverKind solver,
                                             int max_iterations, bool gauss_seidel) {
  FemSettings s;
  s.body_name = body_name;
  s.material = {2300.0, 0.45, 1000.0};
  s.element_model = element;
  s.integrator = TimeIntegrator::kNewmark;
  s.solver = solver;
  s.pcg_max_iterations = max_iterations;
  s.rotated_factor_gauss_seidel = gauss_seidel;
  s.time_step_s = 0.01;
  s.rayleigh_mass_per_s = 1.0;
  s.rayleigh_stiffness_s = 0.01;
  return s;
}

struct SinusoidalPull {
  std::vector<int> nodes;     ///< the force is shared equally among these
  double amplitude_N = 0.0;   ///< summed over the nodes, times direction
  Eigen::Vector3d direction;  ///< not normalised: the box's rows pull along (0.3, 0, 1)
  double frequency_hz = 2.0;
};

inline void ApplyPull(FemBody& body, const SinusoidalPull& pull, Eigen::VectorXd& force) {
  const double share = 1.0 / static_cast<double>(pull.nodes.size());
  const double t = body.state().time_s;
  for (const Eigen::Index node : pull.nodes)
    force.segment<3>(3 * node) =
        pull.amplitude_N * share * std::sin(2.0 * std::numbers::pi * pull.frequency_hz * t) * pull.direction;
  body.SetExternalForces(force);
}

/// The displacements after each of the first `steps` steps of the pull (the untimed first step
/// included), for RunPulledSteps's deviation counter: run it with a converged model.
inline std::vector<Eigen::VectorXd> PulledTrajectory(const std::shared_ptr<const FemModel>& model,
                                                     const SinusoidalPull& pull, int steps) {
  FemBody body(model);
  Eigen::VectorXd force = Eigen::VectorXd::Zero(model->num_dofs());
  std::vector<Eigen::VectorXd> trajectory;
  body.Step();
  trajectory.push_back(body.state().displacement_m);
  while (static_cast<int>(trajectory.size()) < steps) {
    ApplyPull(body, pull, force);
    body.Step();
    trajectory.push_back(body.state().displacement_m);
  }
  return trajectory;
}

/// `reference`, if given, is PulledTrajectory of a converged model: the counter
/// `max_dev_from_converged_um` is the largest distance of a node from its place there, over the
/// steps it covers.
inline void RunPulledSteps(benchmark::State& state, const std::shared_ptr<const FemModel>& model,
                           const SinusoidalPull& pull, const std::vector<Eigen::VectorXd>* reference = nullptr) {
  FemBody body(model);
  Eigen::VectorXd force = Eigen::VectorXd::Zero(model->num_dofs());
  body.Step();
  double iterations = 0.0, residual = 0.0, rejected = 0.0, displacement = 0.0, deviation = 0.0;
  SpectrumCounters spectrum;
  for (auto _ : state) {
    ApplyPull(body, pull, force);
    const StepReport r = body.Step();
    const auto step = static_cast<std::size_t>(body.state().steps - 1);
    if (reference != nullptr && step < reference->size()) {
      state.PauseTiming();
      const Eigen::VectorXd error = body.state().displacement_m - (*reference)[step];
      for (Eigen::Index node = 0; node < error.size() / 3; ++node)
        deviation = std::max(deviation, error.segment<3>(3 * node).norm());
      state.ResumeTiming();
    }
    iterations += r.solver_iterations;
    spectrum.Add(r.solver_spectrum);
    residual = std::max(residual, r.relative_residual);
    rejected += r.accepted ? 0.0 : 1.0;
    for (const Eigen::Index node : pull.nodes)
      displacement = std::max(displacement, body.state().displacement_m.segment<3>(3 * node).norm());
  }
  state.counters["nodes"] = model->num_nodes();
  state.counters["tets"] = model->rest_mesh.num_tets();
  state.counters["pcg_iters"] = benchmark::Counter(iterations, benchmark::Counter::kAvgIterations);
  state.counters["max_rel_residual"] = residual;
  state.counters["rejected"] = rejected;
  state.counters["pulled_max_disp_mm"] = 1e3 * displacement;
  if (reference != nullptr) state.counters["max_dev_from_converged_um"] = 1e6 * deviation;
  spectrum.Report(state);
}

}  // namespace vesica::physics
