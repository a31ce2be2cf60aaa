#include "physics/bem/bem_precompute_cost.h"

#include <cmath>
#include <cstdio>

namespace vesica::physics {
namespace {

// Fitted on the 2-core development machine (OpenBLAS SkylakeX kernels, both cores) to liver-like
// ellipsoids: 752 vertices 0.63 s on a quiet machine (docs/PERFORMANCE.md, BM_BemPrecompute/752);
// 1000 and 2000 vertices 8.2 s and 18.2 s at load average 7 (assembly 4.6 / 11.5 s, dense 3.6 /
// 6.7 s). Assembly per collocation-node x element pair, dense LU + solve per (3n)^3.
constexpr double kAssemblySecondsPerNodePair = 3.0e-7;
constexpr double kDenseSecondsPerCubedDof = 3.0e-11;

}  // namespace

BemPrecomputeCost EstimateBemPrecomputeCost(std::int64_t num_vertices, std::int64_t num_free) {
  const double n = static_cast<double>(num_vertices);
  const double dofs = 3.0 * n;
  BemPrecomputeCost cost;
  cost.peak_bytes = static_cast<std::uint64_t>(8.0 * dofs * (2.0 * dofs + 3.0 * static_cast<double>(num_free)));
  cost.seconds = kAssemblySecondsPerNodePair * n * (2.0 * n) + kDenseSecondsPerCubedDof * dofs * dofs * dofs;
  return cost;
}

std::string DescribeBemPrecomputeCost(std::int64_t num_vertices, const BemPrecomputeCost& cost) {
  char memory[32], time[32], text[128];
  const double bytes = static_cast<double>(cost.peak_bytes);
  if (bytes >= 1e9)
    std::snprintf(memory, sizeof memory, "%.1f GB", bytes / 1e9);
  else
    std::snprintf(memory, sizeof memory, "%.0f MB", std::ceil(bytes / 1e6));
  if (cost.seconds >= 90)
    std::snprintf(time, sizeof time, "%.0f min", std::ceil(cost.seconds / 60.0));
  else
    std::snprintf(time, sizeof time, "%.0f s", std::ceil(cost.seconds));
  std::snprintf(text, sizeof text, "%lld vertices: about %s of memory and %s", static_cast<long long>(num_vertices),
                memory, time);
  return text;
}

}  // namespace vesica::physics
