#include "app/anatomy/surface_relaxation.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <utility>
#include <vector>

#include "physics/mesh/mesh_topology.h"

namespace vesica::app::anatomy {

namespace {

Eigen::Vector3d Gradient(const ImplicitField& field, const Eigen::Vector3d& p) {
  constexpr double kStep = 1e-5;  // metres; well below any feature of the anatomy
  Eigen::Vector3d g;
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d h = Eigen::Vector3d::Zero();
    h[k] = kStep;
    g[k] = (field(p + h) - field(p - h)) / (2 * kStep);
  }
  return g;
}

Eigen::Vector3d ProjectOntoZeroSet(const ImplicitField& field, Eigen::Vector3d p) {
  for (int step = 0; step < 4; ++step) {
    const Eigen::Vector3d g = Gradient(field, p);
    const double g2 = g.squaredNorm();
    if (g2 == 0) break;
    p -= field(p) / g2 * g;
  }
  return p;
}

double AngleAt(const Eigen::Vector3d& apex, const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
  return std::acos(std::clamp((p - apex).normalized().dot((q - apex).normalized()), -1.0, 1.0));
}

// One pass of Delaunay edge flips between nearly coplanar triangles: where the two angles
// opposite an edge sum to more than pi, the other diagonal gives better-shaped triangles.
// Returns the number of flips.
int FlipTowardsDelaunay(physics::TriangleMesh& mesh) {
  constexpr double kMaxFoldCos = 0.94;  // flip only where the normals differ by < ~20 degrees
  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> edge_faces;  // (face, corner)
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.triangles(f, k), b = mesh.triangles(f, (k + 1) % 3);
      edge_faces[{std::min(a, b), std::max(a, b)}].push_back({f, k});
    }
  }
  std::vector<bool> touched(mesh.num_triangles(), false);
  int flips = 0;
  for (const auto& [edge, faces] : edge_faces) {
    if (faces.size() != 2) continue;
    const auto [f1, k1] = faces[0];
    const auto [f2, k2] = faces[1];
    if (touched[f1] || touched[f2]) continue;
    const int a = mesh.triangles(f1, k1), b = mesh.triangles(f1, (k1 + 1) % 3);
    const int c = mesh.triangles(f1, (k1 + 2) % 3), d = mesh.triangles(f2, (k2 + 2) % 3);
    if (c == d || edge_faces.count({std::min(c, d), std::max(c, d)})) continue;
    const Eigen::Vector3d pa = mesh.vertices.row(a), pb = mesh.vertices.row(b);
    const Eigen::Vector3d pc = mesh.vertices.row(c), pd = mesh.vertices.row(d);
    if (AngleAt(pc, pa, pb) + AngleAt(pd, pa, pb) <= std::numbers::pi + 1e-6) continue;
    const Eigen::Vector3d n1 = (pb - pa).cross(pc - pa).normalized();
    const Eigen::Vector3d n2 = (pa - pb).cross(pd - pb).normalized();
    const Eigen::Vector3d m1 = (pd - pa).cross(pc - pa), m2 = (pb - pd).cross(pc - pd);
    if (n1.dot(n2) < kMaxFoldCos || m1.dot(n1) <= 0 || m2.dot(n1) <= 0) continue;
    mesh.triangles.row(f1) << a, d, c;
    mesh.triangles.row(f2) << d, b, c;
    touched[f1] = touched[f2] = true;
    ++flips;
  }
  return flips;
}

}  // namespace

void RelaxOntoField(physics::TriangleMesh& mesh, const ImplicitField& field, int iterations,
                    const ImplicitField& edge_length_m) {
  std::vector<bool> on_boundary(mesh.num_vertices(), false);
  const physics::Triangles adjacency = physics::TriangleAdjacency(mesh);
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    for (int k = 0; k < 3; ++k) {
      if (adjacency(f, k) < 0) on_boundary[mesh.triangles(f, k)] = on_boundary[mesh.triangles(f, (k + 1) % 3)] = true;
    }
  }
  for (int it = 0; it < iterations; ++it) {
    // Flips keep boundary edges (they have one face), so the boundary flags stay valid.
    for (int pass = 0; pass < 10 && FlipTowardsDelaunay(mesh) > 0; ++pass) {
    }
    const auto neighbours = physics::VertexNeighbours(mesh);
    const physics::Vertices previous = mesh.vertices;  // Jacobi update: order-independent
    for (int i = 0; i < mesh.num_vertices(); ++i) {
      if (on_boundary[i] || neighbours[i].empty()) continue;
      const Eigen::Vector3d p = previous.row(i);
      Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
      if (edge_length_m) {
        // In a chain, x_i = sum w_j x_j / sum w_j with w = 1 / h settles at spacings in proportion to h.
        double weights = 0;
        for (int j : neighbours[i]) {
          const double w = 1.0 / edge_length_m(previous.row(j).transpose());
          centroid += w * previous.row(j).transpose();
          weights += w;
        }
        centroid /= weights;
      } else {
        for (int j : neighbours[i]) centroid += previous.row(j).transpose();
        centroid /= static_cast<double>(neighbours[i].size());
      }
      const Eigen::Vector3d n = Gradient(field, p).normalized();
      Eigen::Vector3d move = centroid - p;
      move -= move.dot(n) * n;
      mesh.vertices.row(i) = ProjectOntoZeroSet(field, p + 0.5 * move).transpose();
    }
  }
}

}  // namespace vesica::app::anatomy
