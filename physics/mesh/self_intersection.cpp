#include "physics/mesh/self_intersection.h"

#include <algorithm>
#include <numeric>

#include "physics/mesh/triangle_crossing.h"

namespace vesica::physics {

std::vector<std::pair<int, int>> SelfIntersections(const TriangleMesh& mesh) {
  const int n = mesh.num_triangles();
  std::vector<Eigen::Vector3d> lo(static_cast<std::size_t>(n)), hi(static_cast<std::size_t>(n));
  for (int f = 0; f < n; ++f) {
    lo[f] = hi[f] = mesh.vertices.row(mesh.triangles(f, 0)).transpose();
    for (int k = 1; k < 3; ++k) {
      lo[f] = lo[f].cwiseMin(mesh.vertices.row(mesh.triangles(f, k)).transpose());
      hi[f] = hi[f].cwiseMax(mesh.vertices.row(mesh.triangles(f, k)).transpose());
    }
  }
  // Sweep along the longest axis: a triangle is tested against those whose box is still open.
  const auto [box_lo, box_hi] = BoundingBox(mesh.vertices);
  int axis = 0;
  (box_hi - box_lo).maxCoeff(&axis);
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return lo[a][axis] < lo[b][axis]; });

  std::vector<std::pair<int, int>> pairs;
  std::vector<int> open;
  for (const int f : order) {
    std::erase_if(open, [&](int g) { return hi[g][axis] < lo[f][axis]; });
    for (const int g : open) {
      if ((lo[f].array() > hi[g].array()).any() || (lo[g].array() > hi[f].array()).any()) continue;
      if (TrianglesCross(mesh, f, g)) pairs.emplace_back(std::min(f, g), std::max(f, g));
    }
    open.push_back(f);
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace vesica::physics
