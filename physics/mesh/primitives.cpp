#include "physics/mesh/primitives.h"

#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace vesica::physics {

TetrahedralMesh MakeBoxTetMesh(const Eigen::Vector3d& size, const Eigen::Vector3i& cells) {
  const int nx = cells.x() + 1, ny = cells.y() + 1, nz = cells.z() + 1;
  auto index = [&](int i, int j, int k) { return i + nx * (j + ny * k); };
  TetrahedralMesh mesh;
  mesh.vertices.resize(nx * ny * nz, 3);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        mesh.vertices.row(index(i, j, k)) << size.x() * i / cells.x(), size.y() * j / cells.y(),
            size.z() * k / cells.z();

  // The six monotone paths from corner 000 to corner 111, one per permutation of the axes.
  static constexpr std::array<std::array<int, 3>, 6> kPaths{
      {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  mesh.tets.resize(6 * cells.prod(), 4);
  int t = 0;
  for (int k = 0; k < cells.z(); ++k)
    for (int j = 0; j < cells.y(); ++j)
      for (int i = 0; i < cells.x(); ++i)
        for (const auto& path : kPaths) {
          std::array<int, 3> c{i, j, k};
          std::array<int, 4> tet{};
          tet[0] = index(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[path[s]];
            tet[s + 1] = index(c[0], c[1], c[2]);
          }
          mesh.tets.row(t) << tet[0], tet[1], tet[2], tet[3];
          if (SignedTetVolume(mesh, t) < 0) std::swap(mesh.tets(t, 1), mesh.tets(t, 2));
          ++t;
        }
  return mesh;
}

TriangleMesh MakeIcosphere(double radius, int levels) {
  const double p = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> v{{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0}, {0, -1, p}, {0, 1, p},
                                 {0, -1, -p}, {0, 1, -p}, {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
  for (auto& x : v) x.normalize();
  std::vector<std::array<int, 3>> f{{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                    {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                    {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                    {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      return midpoint[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    next.reserve(f.size() * 4);
    for (const auto& t : f) {
      const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      next.push_back({t[0], ab, ca});
      next.push_back({t[1], bc, ab});
      next.push_back({t[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    f = std::move(next);
  }
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i) mesh.vertices.row(static_cast<Eigen::Index>(i)) = radius * v[i];
  mesh.triangles.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i)
    mesh.triangles.row(static_cast<Eigen::Index>(i)) << f[i][0], f[i][1], f[i][2];
  return mesh;
}

}  // namespace vesica::physics
