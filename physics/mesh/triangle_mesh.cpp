#include "physics/mesh/triangle_mesh.h"

#include <Eigen/Geometry>

namespace vesica::physics {

namespace {
Eigen::Vector3d CornerCross(const TriangleMesh& mesh, int f) {
  const Eigen::Vector3d a = mesh.vertices.row(mesh.triangles(f, 0));
  const Eigen::Vector3d b = mesh.vertices.row(mesh.triangles(f, 1));
  const Eigen::Vector3d c = mesh.vertices.row(mesh.triangles(f, 2));
  return (b - a).cross(c - a);
}
}  // namespace

Eigen::Vector3d TriangleNormal(const TriangleMesh& mesh, int f) {
  return CornerCross(mesh, f).normalized();
}

double TriangleArea(const TriangleMesh& mesh, int f) { return 0.5 * CornerCross(mesh, f).norm(); }

double EnclosedVolume(const TriangleMesh& mesh) {
  double six_volume = 0.0;
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.triangles(f, 0));
    const Eigen::Vector3d b = mesh.vertices.row(mesh.triangles(f, 1));
    const Eigen::Vector3d c = mesh.vertices.row(mesh.triangles(f, 2));
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6.0;
}

std::pair<Eigen::Vector3d, Eigen::Vector3d> BoundingBox(const Vertices& vertices) {
  return {vertices.colwise().minCoeff().transpose(), vertices.colwise().maxCoeff().transpose()};
}

}  // namespace vesica::physics
