#include "physics/bem/bem_model.h"

#include <utility>
#include <vector>

#include "physics/bem/bem_errors.h"
#include "physics/mesh/mesh_validation.h"

namespace vesica::physics {

const char* ToString(BemPrecomputeStage stage) {
  switch (stage) {
    case BemPrecomputeStage::kAssembly: return "assembling the BEM matrices";
    case BemPrecomputeStage::kSolve: return "solving for the Green's functions";
  }
  return "unknown";
}

std::uint64_t BemCacheKey(const TriangleMesh& surface, const ElasticMaterial& material,
                          const BemQuadratureOptions& quadrature) {
  // Bump the tag whenever the assembly or the Green's function layout changes: old files then read
  // as stale instead of being trusted.
  std::uint64_t h = HashBytes("vesica-bem-greens-v1", 20, 0);
  h = HashBytes(surface.vertices.data(), sizeof(double) * surface.vertices.size(), h);
  h = HashBytes(surface.triangles.data(), sizeof(int) * surface.triangles.size(), h);
  std::vector<unsigned char> fixed(static_cast<std::size_t>(surface.num_vertices()), 0);
  for (Eigen::Index i = 0; i < surface.vertex_labels.size() && i < surface.num_vertices(); ++i)
    fixed[static_cast<std::size_t>(i)] = (surface.vertex_labels(i) & kLabelFixed) ? 1 : 0;
  h = HashBytes(fixed.data(), fixed.size(), h);
  const double numbers[] = {material.youngs_modulus_Pa, material.poisson_ratio,
                            quadrature.near_ratio, quadrature.far_ratio};
  h = HashBytes(numbers, sizeof(numbers), h);
  const int integers[] = {quadrature.duffy_order, quadrature.max_subdivision};
  return HashBytes(integers, sizeof(integers), h);
}

BemModel PrecomputeBemModel(const TriangleMesh& surface, const ElasticMaterial& material,
                            const std::string& source, const BemPrecomputeOptions& options,
                            GreensCacheStatus* cache_status) {
  ValidateTriangleMesh(surface, source, SurfaceRequirement::kClosed);
  ValidateBemMaterial(material);
  BemModel model;
  model.rest_surface = surface;
  model.material = material;
  model.layout = MakeBemNodeLayout(surface, source);
  model.lumped_area_m2 = Eigen::VectorXd::Zero(surface.num_vertices());
  for (int f = 0; f < surface.num_triangles(); ++f)
    for (int c = 0; c < 3; ++c)
      model.lumped_area_m2(surface.triangles(f, c)) += TriangleArea(surface, f) / 3.0;

  const Eigen::Index rows = 3 * surface.num_vertices();
  const Eigen::Index cols = 3 * static_cast<Eigen::Index>(model.layout.free_nodes.size());
  const std::uint64_t key = BemCacheKey(surface, material, options.quadrature);
  GreensCacheStatus status = GreensCacheStatus::kMissing;
  std::string unreadable_reason;
  if (!options.cache_path.empty()) {
    if (auto cached = ReadGreensCache(options.cache_path, key, status, &unreadable_reason)) {
      if (cached->rows() == rows && cached->cols() == cols) {
        model.greens = std::move(*cached);
      } else {
        status = GreensCacheStatus::kCorrupt;
      }
    }
  }
  if (cache_status) *cache_status = status;
  if (model.greens.size() > 0) return model;

  const BemPrecomputeCost cost =
      EstimateBemPrecomputeCost(surface.num_vertices(), static_cast<std::int64_t>(model.layout.free_nodes.size()));
  if (options.max_peak_bytes > 0 && cost.peak_bytes > options.max_peak_bytes) {
    throw BemError(source + ": too large for the BEM liver: " + DescribeBemPrecomputeCost(surface.num_vertices(), cost) +
                   " (limit " + std::to_string(options.max_peak_bytes >> 20) +
                   " MiB); decimate the surface to about 1000-2000 vertices");
  }
  bool warned = false;
  const auto warn = [&](const std::string& message) {
    if (options.on_warning && !warned) options.on_warning(message);
    warned = true;
  };
  if (cost.seconds > options.warn_after_s) {
    warn(source + ": the BEM precompute of " + DescribeBemPrecomputeCost(surface.num_vertices(), cost) +
         " (the Green's functions are cached afterwards)");
    warned = false;  // a cache problem below is still worth its own line
  }
  const auto progress = [&](BemPrecomputeStage stage, double fraction) {
    if (options.on_progress) options.on_progress(stage, fraction);
  };
  BemMatrices matrices = AssembleBemMatrices(surface, material, options.quadrature,
                                             [&](double f) { progress(BemPrecomputeStage::kAssembly, f); });
  progress(BemPrecomputeStage::kSolve, 0.0);
  model.greens = ComputeGreensFunctions(std::move(matrices), model.layout);
  progress(BemPrecomputeStage::kSolve, 1.0);
  if (options.cache_path.empty()) return model;
  try {
    WriteGreensCache(options.cache_path, key, model.greens);
  } catch (const BemError& e) {
    // The cache is an optimisation: the session runs uncached, and the user hears why once.
    warn(std::string(e.what()) + "; running without the cache (the next start computes it again)");
  }
  return model;
}

}  // namespace vesica::physics
