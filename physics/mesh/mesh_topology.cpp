#include "physics/mesh/mesh_topology.h"

#include <algorithm>
#include <array>
#include <map>
#include <unordered_map>

namespace vesica::physics {

namespace {

void SortUnique(std::vector<std::vector<int>>& lists) {
  for (auto& l : lists) {
    std::sort(l.begin(), l.end());
    l.erase(std::unique(l.begin(), l.end()), l.end());
  }
}

template <typename Elements>
std::vector<std::vector<int>> NeighboursOfElements(const Elements& elements, int num_vertices) {
  std::vector<std::vector<int>> n(num_vertices);
  const int corners = static_cast<int>(elements.cols());
  for (int e = 0; e < elements.rows(); ++e)
    for (int i = 0; i < corners; ++i)
      for (int j = 0; j < corners; ++j)
        if (i != j) n[elements(e, i)].push_back(elements(e, j));
  SortUnique(n);
  return n;
}

template <typename Elements>
std::vector<std::vector<int>> IncidentElements(const Elements& elements, int num_vertices) {
  std::vector<std::vector<int>> inc(num_vertices);
  for (int e = 0; e < elements.rows(); ++e)
    for (int i = 0; i < elements.cols(); ++i) inc[elements(e, i)].push_back(e);
  return inc;
}

std::uint64_t EdgeKey(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
}

}  // namespace

std::vector<std::vector<int>> VertexNeighbours(const TriangleMesh& mesh) {
  return NeighboursOfElements(mesh.triangles, mesh.num_vertices());
}
std::vector<std::vector<int>> VertexNeighbours(const TetrahedralMesh& mesh) {
  return NeighboursOfElements(mesh.tets, mesh.num_vertices());
}
std::vector<std::vector<int>> IncidentTriangles(const TriangleMesh& mesh) {
  return IncidentElements(mesh.triangles, mesh.num_vertices());
}
std::vector<std::vector<int>> IncidentTets(const TetrahedralMesh& mesh) {
  return IncidentElements(mesh.tets, mesh.num_vertices());
}

Triangles TriangleAdjacency(const TriangleMesh& mesh) {
  // Each undirected edge collects the (triangle, local edge) pairs that use it.
  std::unordered_map<std::uint64_t, std::vector<std::pair<int, int>>> users;
  users.reserve(static_cast<std::size_t>(mesh.num_triangles()) * 2);
  for (int f = 0; f < mesh.num_triangles(); ++f)
    for (int k = 0; k < 3; ++k)
      users[EdgeKey(mesh.triangles(f, k), mesh.triangles(f, (k + 1) % 3))].emplace_back(f, k);
  Triangles adjacency = Triangles::Constant(mesh.num_triangles(), 3, -1);
  for (const auto& [key, list] : users) {
    if (list.size() == 2) {
      adjacency(list[0].first, list[0].second) = list[1].first;
      adjacency(list[1].first, list[1].second) = list[0].first;
    } else if (list.size() > 2) {
      for (const auto& [f, k] : list) adjacency(f, k) = -2;
    }
  }
  return adjacency;
}

std::array<int, 3> TetFaceCorners(int k) {
  // For a positive tet (0,1,2,3): face opposite 0 is (1,2,3) with outward normal, etc.
  static constexpr std::array<std::array<int, 3>, 4> kFaces{
      {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}}};
  return kFaces[k];
}

TetBoundary ExtractBoundary(const TetrahedralMesh& mesh) {
  // A face is on the boundary when exactly one tet uses it; key it by its sorted corners.
  std::map<std::array<int, 3>, std::pair<int, int>> first_use;  // sorted face -> (tet, local)
  std::map<std::array<int, 3>, int> use_count;
  for (int t = 0; t < mesh.num_tets(); ++t) {
    for (int k = 0; k < 4; ++k) {
      const auto c = TetFaceCorners(k);
      std::array<int, 3> key{mesh.tets(t, c[0]), mesh.tets(t, c[1]), mesh.tets(t, c[2])};
      std::sort(key.begin(), key.end());
      if (++use_count[key] == 1) first_use[key] = {t, k};
    }
  }
  std::vector<std::pair<int, int>> faces;
  for (const auto& [key, count] : use_count)
    if (count == 1) faces.push_back(first_use[key]);
  std::sort(faces.begin(), faces.end());

  TetBoundary b;
  b.volume_to_surface = Eigen::VectorXi::Constant(mesh.num_vertices(), -1);
  std::vector<int> surface_to_volume;
  b.surface.triangles.resize(static_cast<Eigen::Index>(faces.size()), 3);
  b.face_tet.resize(static_cast<Eigen::Index>(faces.size()));
  b.face_local.resize(static_cast<Eigen::Index>(faces.size()));
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto [t, k] = faces[f];
    const auto c = TetFaceCorners(k);
    for (int i = 0; i < 3; ++i) {
      const int v = mesh.tets(t, c[i]);
      if (b.volume_to_surface[v] < 0) {
        b.volume_to_surface[v] = static_cast<int>(surface_to_volume.size());
        surface_to_volume.push_back(v);
      }
      b.surface.triangles(static_cast<Eigen::Index>(f), i) = b.volume_to_surface[v];
    }
    b.face_tet[static_cast<Eigen::Index>(f)] = t;
    b.face_local[static_cast<Eigen::Index>(f)] = k;
  }
  b.surface_to_volume =
      Eigen::Map<Eigen::VectorXi>(surface_to_volume.data(), static_cast<Eigen::Index>(surface_to_volume.size()));
  b.surface.vertices.resize(b.surface_to_volume.size(), 3);
  for (Eigen::Index i = 0; i < b.surface_to_volume.size(); ++i)
    b.surface.vertices.row(i) = mesh.vertices.row(b.surface_to_volume[i]);
  return b;
}

}  // namespace vesica::physics
