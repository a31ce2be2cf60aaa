#pragma once
// The fastest repetition, reported next to Google Benchmark's mean / median / stddev
// (`--benchmark_repetitions=N` gives `<name>_min`). On the shared development VM other tenants'
// bursts only ever slow a run down, so the minimum of repeated runs is the steadiest figure for a
// before / after comparison (docs/performance/fem.md). Rate counters get their minimum too.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <vector>

namespace vesica::physics {

inline double MinimumOf(const std::vector<double>& values) {
  return values.empty() ? 0.0 : *std::min_element(values.begin(), values.end());
}

inline benchmark::internal::Benchmark* WithMinimum(benchmark::internal::Benchmark* b) {
  return b->ComputeStatistics("min", MinimumOf);
}

}  // namespace vesica::physics
