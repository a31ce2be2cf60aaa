#include "physics/bem/graded_surface_refinement.h"

#include <array>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "physics/mesh/mesh_validation.h"

namespace vesica::physics {
namespace {

using Edge = std::pair<int, int>;
Edge Key(int a, int b) { return a < b ? Edge{a, b} : Edge{b, a}; }

// One red-green pass over `tris`, growing `vertices` and `labels`; parents follow their children.
void RefinePass(std::vector<Eigen::Vector3d>& vertices, std::vector<int>& labels, std::vector<std::array<int, 3>>& tris,
                std::vector<int>& parents, const Vertices& centres, double radius) {
  std::vector<bool> near(vertices.size(), false);
  for (std::size_t v = 0; v < vertices.size(); ++v)
    near[v] = ((centres.rowwise() - vertices[v].transpose()).rowwise().squaredNorm().array() < radius * radius).any();
  std::vector<bool> red(tris.size(), false);
  for (std::size_t f = 0; f < tris.size(); ++f)
    for (int v : tris[f])
      if (near[static_cast<std::size_t>(v)]) red[f] = true;
  std::map<Edge, int> split;
  for (bool changed = true; changed;) {  // close: two or three split edges make a triangle red
    split.clear();
    for (std::size_t f = 0; f < tris.size(); ++f)
      if (red[f])
        for (int c = 0; c < 3; ++c) split[Key(tris[f][c], tris[f][(c + 1) % 3])] = -1;
    changed = false;
    for (std::size_t f = 0; f < tris.size(); ++f) {
      if (red[f]) continue;
      int cut = 0;
      for (int c = 0; c < 3; ++c) cut += split.count(Key(tris[f][c], tris[f][(c + 1) % 3])) ? 1 : 0;
      if (cut >= 2) red[f] = changed = true;
    }
  }
  for (auto& [edge, mid] : split) {  // std::map: midpoints numbered in edge order, deterministic
    mid = static_cast<int>(vertices.size());
    vertices.push_back(
        0.5 * (vertices[static_cast<std::size_t>(edge.first)] + vertices[static_cast<std::size_t>(edge.second)]));
    labels.push_back(labels[static_cast<std::size_t>(edge.first)] & labels[static_cast<std::size_t>(edge.second)]);
  }
  const auto mid = [&](int a, int b) {
    const auto it = split.find(Key(a, b));
    return it == split.end() ? -1 : it->second;
  };
  std::vector<std::array<int, 3>> out;
  std::vector<int> out_parents;
  for (std::size_t f = 0; f < tris.size(); ++f) {
    const auto [a, b, c] = tris[f];
    std::vector<std::array<int, 3>> children;
    if (red[f]) {
      const int ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      children = {{a, ab, ca}, {ab, b, bc}, {ca, bc, c}, {ab, bc, ca}};
    } else {
      children = {tris[f]};
      for (const auto& [p, q, o] : {std::array{a, b, c}, std::array{b, c, a}, std::array{c, a, b}})
        if (const int x = mid(p, q); x >= 0) children = {{p, x, o}, {x, q, o}};
    }
    for (const auto& t : children) {
      out.push_back(t);
      out_parents.push_back(parents[f]);
    }
  }
  tris = std::move(out);
  parents = std::move(out_parents);
}

}  // namespace

RefinedSurface RefineTowardPoint(const TriangleMesh& surface, const Eigen::Vector3d& centre_m,
                                 std::span<const double> radii_m) {
  return RefineTowardPoints(surface, Vertices(centre_m.transpose()), radii_m);
}

RefinedSurface RefineTowardPoints(const TriangleMesh& surface, const Vertices& centres_m,
                                  std::span<const double> radii_m) {
  for (std::size_t k = 0; k < radii_m.size(); ++k)
    if (!(std::isfinite(radii_m[k]) && radii_m[k] > 0))
      throw MeshError("RefineTowardPoints: radius " + std::to_string(k) + " is " + std::to_string(radii_m[k]) +
                      " m; each refinement radius must be positive and finite");
  std::vector<Eigen::Vector3d> vertices;
  std::vector<int> labels;
  for (int v = 0; v < surface.num_vertices(); ++v) {
    vertices.push_back(surface.vertices.row(v).transpose());
    labels.push_back(surface.vertex_labels.size() == surface.num_vertices() ? surface.vertex_labels(v) : 0);
  }
  std::vector<std::array<int, 3>> tris;
  std::vector<int> parents;
  for (int f = 0; f < surface.num_triangles(); ++f) {
    tris.push_back({surface.triangles(f, 0), surface.triangles(f, 1), surface.triangles(f, 2)});
    parents.push_back(f);
  }
  for (double radius : radii_m) RefinePass(vertices, labels, tris, parents, centres_m, radius);

  RefinedSurface out;
  out.surface.vertices.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  for (std::size_t v = 0; v < vertices.size(); ++v)
    out.surface.vertices.row(static_cast<Eigen::Index>(v)) = vertices[v];
  out.surface.triangles.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (std::size_t f = 0; f < tris.size(); ++f)
    for (int c = 0; c < 3; ++c)
      out.surface.triangles(static_cast<Eigen::Index>(f), c) = tris[f][static_cast<std::size_t>(c)];
  if (surface.vertex_labels.size() == surface.num_vertices())
    out.surface.vertex_labels =
        Eigen::Map<const Eigen::VectorXi>(labels.data(), static_cast<Eigen::Index>(labels.size()));
  out.parent_triangle = Eigen::Map<const Eigen::VectorXi>(parents.data(), static_cast<Eigen::Index>(parents.size()));
  return out;
}

}  // namespace vesica::physics
