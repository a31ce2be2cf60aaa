#pragma once
// The precomputed, read-only part of a BEM body (STYLE.md 2 and 4): the rest surface, material,
// fixed region and the reference problem's Green's functions. Built once (or read from the cache);
// the run-time capacitance solver (capacitance_solver.h) only reads it.

#include <Eigen/Core>
#include <string>

#include "physics/bem/bem_matrices.h"
#include "physics/bem/bem_reference_problem.h"
#include "physics/bem/bem_material.h"
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

struct BemPrecomputeOptions {
  std::string cache_path;  ///< empty: no cache; else read if valid, (re)write otherwise
  BemQuadratureOptions quadrature;
};

/// Validates the surface (closed, manifold, outward: MeshError naming `source`), the material and
/// the fixed region (BemError), then reads the Green's functions from the cache or computes them.
/// `cache_status` (optional) reports what the cache held; kMissing/kStale/kCorrupt mean rebuilt.
BemModel PrecomputeBemModel(const TriangleMesh& surface, const ElasticMaterial& material,
                            const std::string& source, const BemPrecomputeOptions& options = {},
                            GreensCacheStatus* cache_status = nullptr);

/// The cache key: hash of vertices, triangles, fixed region, material, quadrature and format.
std::uint64_t BemCacheKey(const TriangleMesh& surface, const ElasticMaterial& material,
                          const BemQuadratureOptions& quadrature);

}  // namespace vesica::physics
