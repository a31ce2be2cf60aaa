#pragma once
// The precomputed, read-only part of a BEM body (STYLE.md 2 and 4): the rest surface, material,
// fixed region and the reference problem's Green's functions. Built once (or read from the cache);
// the run-time capacitance solver (capacitance_solver.h) only reads it.

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>

#include "physics/bem/bem_matrices.h"
#include "physics/bem/bem_reference_problem.h"
#include "physics/bem/bem_material.h"
#include "physics/bem/bem_precompute_cost.h"
#include "physics/bem/greens_function_cache.h"
#include "physics/mesh/triangle_mesh.h"

namespace vesica::physics {

struct BemModel {
  TriangleMesh rest_surface;     ///< metres; vertex_labels mark the fixed region
  ElasticMaterial material;
  BemNodeLayout layout;
  Eigen::VectorXd lumped_area_m2;  ///< #V: a third of the adjacent triangles' area (force = t * A)
  Eigen::MatrixXd greens;          ///< Xi, 3#V x 3#free (see ComputeGreensFunctions), m/Pa and 1

  int num_nodes() const { return rest_surface.num_vertices(); }
};

/// Stages the precompute reports through BemPrecomputeOptions::on_progress.
enum class BemPrecomputeStage {
  kAssembly,  ///< H and G, row by row (fraction of rows)
  kSolve,     ///< dense LU of the reference problem and the Green's functions (0 at its start, 1 at its end)
};
const char* ToString(BemPrecomputeStage stage);

struct BemPrecomputeOptions {
  std::string cache_path;  ///< empty: no cache; else read if valid, (re)write otherwise
  BemQuadratureOptions quadrature;
  /// A surface whose precompute would hold more than this at its peak is refused (BemError
  /// naming the memory and time it would take). Bytes; 0: no limit.
  std::uint64_t max_peak_bytes = std::uint64_t{4} << 30;
  /// Beyond this estimated time (s) on_warning is told the cost before the precompute starts.
  double warn_after_s = 20.0;
  /// Progress of a precompute that runs (not called when the cache is used); calling thread.
  std::function<void(BemPrecomputeStage, double fraction)> on_progress;
  /// What the caller should tell the user, once each: the precompute will be long (its cost), the
  /// cache could not be read or written (the model is then computed and used uncached).
  std::function<void(const std::string&)> on_warning;
};

/// Validates the surface (closed, manifold, outward: MeshError naming `source`), the material and
/// the fixed region (BemError), then reads the Green's functions from the cache or computes them.
/// `cache_status` (optional) reports what the cache held; kMissing/kStale/kCorrupt/kUnreadable
/// mean rebuilt. A cache that cannot be read or written never fails the precompute: it is
/// reported through on_warning. Throws BemError naming the cost when it exceeds max_peak_bytes.
BemModel PrecomputeBemModel(const TriangleMesh& surface, const ElasticMaterial& material,
                            const std::string& source, const BemPrecomputeOptions& options = {},
                            GreensCacheStatus* cache_status = nullptr);

/// The cache key: hash of vertices, triangles, fixed region, material, quadrature and format.
std::uint64_t BemCacheKey(const TriangleMesh& surface, const ElasticMaterial& material,
                          const BemQuadratureOptions& quadrature);

}  // namespace vesica::physics
