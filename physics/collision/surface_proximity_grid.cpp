#include "physics/collision/surface_proximity_grid.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "physics/mesh/barycentric.h"

namespace vesica::physics {

SurfaceProximityGrid::SurfaceProximityGrid(const TriangleMesh& rest, double reach_m, double cell_m)
    : triangles_(rest.triangles), cell_m_(cell_m), reach_m_(reach_m) {
  if (rest.num_triangles() == 0 || rest.num_vertices() == 0)
    throw std::invalid_argument("SurfaceProximityGrid: the surface has no triangles");
  if (!(reach_m > 0.0) || !(cell_m > 0.0))
    throw std::invalid_argument("SurfaceProximityGrid: reach_m " + std::to_string(reach_m) + " and cell_m " +
                                std::to_string(cell_m) + " must be > 0");
  const Eigen::Vector3d lo = rest.vertices.colwise().minCoeff().transpose() - Eigen::Vector3d::Constant(reach_m);
  const Eigen::Vector3d hi = rest.vertices.colwise().maxCoeff().transpose() + Eigen::Vector3d::Constant(reach_m);
  origin_ = lo;
  for (int a = 0; a < 3; ++a) cells_[a] = std::max(1, static_cast<int>(std::ceil((hi[a] - lo[a]) / cell_m)));
  const int num_cells = cells_.prod();
  std::vector<std::vector<int>> lists(static_cast<size_t>(num_cells));
  for (int f = 0; f < rest.num_triangles(); ++f) {
    Eigen::Vector3d box_lo = Eigen::Vector3d::Constant(1e300), box_hi = Eigen::Vector3d::Constant(-1e300);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d v = rest.vertices.row(rest.triangles(f, k)).transpose();
      box_lo = box_lo.cwiseMin(v);
      box_hi = box_hi.cwiseMax(v);
    }
    Eigen::Vector3i c0, c1;
    for (int a = 0; a < 3; ++a) {
      c0[a] = std::clamp(static_cast<int>(std::floor((box_lo[a] - reach_m - origin_[a]) / cell_m)), 0, cells_[a] - 1);
      c1[a] = std::clamp(static_cast<int>(std::floor((box_hi[a] + reach_m - origin_[a]) / cell_m)), 0, cells_[a] - 1);
    }
    for (int i = c0[0]; i <= c1[0]; ++i)
      for (int j = c0[1]; j <= c1[1]; ++j)
        for (int k = c0[2]; k <= c1[2]; ++k)
          lists[static_cast<size_t>((i * cells_[1] + j) * cells_[2] + k)].push_back(f);
  }
  cell_start_.assign(static_cast<size_t>(num_cells) + 1, 0);
  for (int c = 0; c < num_cells; ++c)
    cell_start_[static_cast<size_t>(c) + 1] =
        cell_start_[static_cast<size_t>(c)] + static_cast<int>(lists[static_cast<size_t>(c)].size());
  cell_triangles_.reserve(static_cast<size_t>(cell_start_.back()));
  for (const auto& list : lists) cell_triangles_.insert(cell_triangles_.end(), list.begin(), list.end());
}

SurfaceProximityGrid::Frame SurfaceProximityGrid::MakeFrame(const Vertices& vertices) const {
  Frame frame;
  frame.vertices = &vertices;
  const Eigen::Index n = triangles_.rows();
  frame.centres.resize(n, 3);
  frame.normals.resize(n, 3);
  frame.radii.resize(n);
  for (Eigen::Index f = 0; f < n; ++f) {
    const Eigen::Vector3d a = vertices.row(triangles_(f, 0)).transpose();
    const Eigen::Vector3d b = vertices.row(triangles_(f, 1)).transpose();
    const Eigen::Vector3d c = vertices.row(triangles_(f, 2)).transpose();
    const Eigen::Vector3d centre = (a + b + c) / 3.0;
    frame.centres.row(f) = centre.transpose();
    frame.radii[f] =
        std::sqrt(std::max({(a - centre).squaredNorm(), (b - centre).squaredNorm(), (c - centre).squaredNorm()}));
    frame.normals.row(f) = (b - a).cross(c - a).normalized().transpose();
  }
  return frame;
}

std::optional<SurfaceProximity> SurfaceProximityGrid::Nearest(const Eigen::Vector3d& p_W, const Frame& frame,
                                                              double max_distance_m) const {
  if (empty()) return std::nullopt;
  int cell = 0;
  for (int a = 0; a < 3; ++a) {
    const double u = std::floor((p_W[a] - origin_[a]) / cell_m_);
    if (!(u >= 0.0 && u < cells_[a])) return std::nullopt;  // outside the grid: farther than reach
    cell = cell * cells_[a] + static_cast<int>(u);
  }
  const Vertices& vertices = *frame.vertices;
  std::optional<SurfaceProximity> best;
  double best_distance = max_distance_m;
  for (int k = cell_start_[static_cast<size_t>(cell)]; k < cell_start_[static_cast<size_t>(cell) + 1]; ++k) {
    const int f = cell_triangles_[static_cast<size_t>(k)];
    // No point of the triangle is nearer than its bounding sphere.
    if ((p_W - frame.centres.row(f).transpose()).norm() - frame.radii[f] > best_distance) continue;
    const Eigen::Vector3d a = vertices.row(triangles_(f, 0)).transpose();
    const Eigen::Vector3d b = vertices.row(triangles_(f, 1)).transpose();
    const Eigen::Vector3d c = vertices.row(triangles_(f, 2)).transpose();
    const TrianglePoint cp = ClosestPointOnTriangle(p_W, a, b, c);
    const double distance = (p_W - cp.point).norm();
    if (distance > best_distance) continue;
    const Eigen::Vector3d n = frame.normals.row(f).transpose();
    if (best && distance == best_distance) {
      // A tie (the point nearest an edge or vertex): keep the triangle facing the point most squarely.
      if (std::abs(n.dot(p_W - cp.point)) <= std::abs(best->normal_W.dot(p_W - cp.point))) continue;
    }
    best_distance = distance;
    best = SurfaceProximity{f, cp.point, n, n.dot(p_W - cp.point) >= 0.0 ? distance : -distance};
  }
  return best;
}

}  // namespace vesica::physics
