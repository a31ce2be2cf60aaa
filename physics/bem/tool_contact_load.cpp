#include "physics/bem/tool_contact_load.h"

#include <cmath>
#include <string>

#include "physics/bem/bem_errors.h"
#include "physics/bem/tool_footprint.h"

namespace vesica::physics {

BemContactLoad MakeToolContactLoad(const BemModel& model, int triangle, const Eigen::Vector3d& weights,
                                   const Eigen::Vector3d& normal_W, double radius_m) {
  const TriangleMesh& surface = model.rest_surface;
  if (triangle < 0 || triangle >= surface.num_triangles())
    throw BemError("tool contact load: triangle " + std::to_string(triangle) + " out of range [0, " +
                   std::to_string(surface.num_triangles()) + ")");
  if (!weights.allFinite() || weights.minCoeff() < -1e-6 || std::abs(weights.sum() - 1.0) > 1e-6)
    throw BemError("tool contact load: weights (" + std::to_string(weights.x()) + ", " + std::to_string(weights.y()) +
                   ", " + std::to_string(weights.z()) + ") are not barycentric");
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (int c = 0; c < 3; ++c) centre += weights[c] * surface.vertices.row(surface.triangles(triangle, c)).transpose();
  FootprintOptions options;
  options.shapes = {FootprintShape::kPunch};
  options.subdivision_levels = 2;  // the study's force moves by 0.5 % from 2 to 6 levels
  const FootprintModes modes = MakeFootprintModes(
      surface, model.lumped_area_m2, DiscFootprint(surface, triangle, centre, normal_W, radius_m), options);
  return {modes.nodes, modes.load_weights.col(0), modes.traction_per_N.col(0)};
}

Eigen::Matrix3d ContactLoadCompliance(const BemModel& model, const BemContactLoad& a, const BemContactLoad& b) {
  Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
  for (std::size_t j = 0; j < b.nodes.size(); ++j) {
    const int fj = model.layout.free_index(b.nodes[j]);
    if (fj < 0) continue;  // a force on the fixed region moves nothing
    for (std::size_t i = 0; i < a.nodes.size(); ++i) {
      if (model.layout.free_index(a.nodes[i]) < 0) continue;
      c += a.load_weights(static_cast<Eigen::Index>(i)) * b.traction_per_N(static_cast<Eigen::Index>(j)) *
           model.greens.block<3, 3>(3 * a.nodes[i], 3 * fj);
    }
  }
  return c;
}

void AddContactLoadResponse(const BemModel& model, const BemContactLoad& load, const Eigen::Vector3d& force_N,
                            Eigen::VectorXd& du) {
  for (std::size_t j = 0; j < load.nodes.size(); ++j) {
    const int fj = model.layout.free_index(load.nodes[j]);
    if (fj >= 0)
      du.noalias() +=
          model.greens.middleCols<3>(3 * fj) * (load.traction_per_N(static_cast<Eigen::Index>(j)) * force_N);
  }
}

}  // namespace vesica::physics
