#include "physics/tissue/spring_forces.h"

#include <stdexcept>
#include <string>

namespace vesica::physics {

Eigen::Vector3d SpringForceOnGallbladder(const Eigen::Vector3d& x_gallbladder, const Eigen::Vector3d& x_liver,
                                         const Eigen::Vector3d& v_gallbladder, const Eigen::Vector3d& v_liver,
                                         double rest_length, const SpringMaterial& material) {
  const Eigen::Vector3d d = x_liver - x_gallbladder;
  const double length = d.norm();
  if (length == 0.0) return Eigen::Vector3d::Zero();  // direction undefined
  const Eigen::Vector3d u = d / length;
  const double tension =
      material.stiffness * (length - rest_length) + material.damping * (v_liver - v_gallbladder).dot(u);
  return tension * u;
}

TissueNodalForces ComputeTissueForces(const ConnectiveTissue& tissue, const TetrahedralMesh& gb,
                                      const Vertices& gb_velocities, const TriangleMesh& liver,
                                      const Vertices& liver_velocities, const SpringMaterial& material) {
  if (material.stiffness < 0.0 || material.damping < 0.0)
    throw std::invalid_argument("ComputeTissueForces: stiffness and damping must be >= 0");
  if (gb_velocities.rows() != gb.num_vertices() || liver_velocities.rows() != liver.num_vertices())
    throw std::invalid_argument("ComputeTissueForces: velocities have " + std::to_string(gb_velocities.rows()) + " / " +
                                std::to_string(liver_velocities.rows()) + " rows, meshes have " +
                                std::to_string(gb.num_vertices()) + " / " + std::to_string(liver.num_vertices()) +
                                " vertices");
  TissueNodalForces out{Vertices::Zero(gb.num_vertices(), 3), Vertices::Zero(liver.num_vertices(), 3), {}};
  for (const TissueSpring& s : tissue.springs) {
    if (!s.alive) continue;
    const Eigen::Vector3d f =
        SpringForceOnGallbladder(GallbladderEnd(s, gb.vertices, gb.tets), LiverEnd(s, liver.vertices, liver.triangles),
                                 GallbladderEnd(s, gb_velocities, gb.tets),
                                 LiverEnd(s, liver_velocities, liver.triangles), s.rest_length, material);
    // Barycentric transpose: a point force spreads to the nodes by the same weights.
    for (int k = 0; k < 4; ++k)
      out.gallbladder.row(gb.tets(s.gallbladder_tet, k)) += s.gallbladder_weights[k] * f.transpose();
    out.liver_points.push_back({s.liver_triangle, s.liver_weights, -f});
    for (int k = 0; k < 3; ++k)
      out.liver.row(liver.triangles(s.liver_triangle, k)) -= s.liver_weights[k] * f.transpose();
  }
  return out;
}

}  // namespace vesica::physics
