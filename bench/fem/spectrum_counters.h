#pragma once
// The widest spectrum of the preconditioned system over a benchmark's steps, from each PCG solve's
// Lanczos estimate (StepReport::solver_spectrum): counters spectrum_min / spectrum_max say how
// well the preconditioner fits, and so why a row takes the iterations it does.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <limits>

#include "physics/fem/cg_spectrum_estimate.h"

namespace vesica::physics {

class SpectrumCounters {
 public:
  void Add(const SpectrumEstimate& e) {
    if (!(e.smallest > 0.0)) return;  // a direct solve or no iteration
    smallest_ = std::min(smallest_, e.smallest);
    largest_ = std::max(largest_, e.largest);
  }
  /// Nothing when no step iterated (a direct solver's rows).
  void Report(benchmark::State& state) const {
    if (largest_ == 0.0) return;
    state.counters["spectrum_min"] = smallest_;
    state.counters["spectrum_max"] = largest_;
  }

 private:
  double smallest_ = std::numeric_limits<double>::infinity();
  double largest_ = 0.0;
};

}  // namespace vesica::physics
