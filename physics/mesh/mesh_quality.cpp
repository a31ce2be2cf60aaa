#include "physics/mesh/mesh_quality.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "physics/mesh/mesh_topology.h"

namespace vesica::physics {

namespace {
std::array<Eigen::Vector3d, 4> Corners(const TetrahedralMesh& mesh, int t) {
  return {mesh.vertices.row(mesh.tets(t, 0)).transpose(), mesh.vertices.row(mesh.tets(t, 1)).transpose(),
          mesh.vertices.row(mesh.tets(t, 2)).transpose(), mesh.vertices.row(mesh.tets(t, 3)).transpose()};
}

std::array<double, 6> DihedralAnglesDeg(const TetrahedralMesh& mesh, int t) {
  const auto x = Corners(mesh, t);
  std::array<Eigen::Vector3d, 4> n;  // outward face normals, face k opposite corner k
  for (int k = 0; k < 4; ++k) {
    const auto c = TetFaceCorners(k);
    n[k] = (x[c[1]] - x[c[0]]).cross(x[c[2]] - x[c[0]]).normalized();
  }
  std::array<double, 6> angles{};
  int a = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      angles[a++] = (std::numbers::pi - std::acos(std::clamp(n[i].dot(n[j]), -1.0, 1.0))) * 180.0 / std::numbers::pi;
  return angles;
}
}  // namespace

double MinDihedralAngleDeg(const TetrahedralMesh& mesh, int t) {
  const auto a = DihedralAnglesDeg(mesh, t);
  return *std::min_element(a.begin(), a.end());
}

double RadiusEdgeRatio(const TetrahedralMesh& mesh, int t) {
  const auto x = Corners(mesh, t);
  // Circumcentre c solves 2 (x_i - x_0) . c' = |x_i - x_0|^2 with c' = c - x_0.
  Eigen::Matrix3d A;
  Eigen::Vector3d b;
  for (int i = 1; i < 4; ++i) {
    A.row(i - 1) = 2.0 * (x[i] - x[0]).transpose();
    b[i - 1] = (x[i] - x[0]).squaredNorm();
  }
  const double radius = A.partialPivLu().solve(b).norm();
  double shortest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) shortest = std::min(shortest, (x[i] - x[j]).norm());
  return radius / shortest;
}

TetQualitySummary MeasureTetQuality(const TetrahedralMesh& mesh) {
  TetQualitySummary s{180.0, 0.0, 0.0, 0.0};
  for (int t = 0; t < mesh.num_tets(); ++t) {
    const auto a = DihedralAnglesDeg(mesh, t);
    s.min_dihedral_deg = std::min(s.min_dihedral_deg, *std::min_element(a.begin(), a.end()));
    s.max_dihedral_deg = std::max(s.max_dihedral_deg, *std::max_element(a.begin(), a.end()));
    const double r = RadiusEdgeRatio(mesh, t);
    s.max_radius_edge = std::max(s.max_radius_edge, r);
    s.mean_radius_edge += r;
  }
  if (mesh.num_tets() > 0) s.mean_radius_edge /= mesh.num_tets();
  return s;
}

}  // namespace vesica::physics
