#include "app/anatomy/surface_relaxation.h"

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

}  // namespace

void RelaxOntoField(physics::TriangleMesh& mesh, const ImplicitField& field, int iterations) {
  const auto neighbours = physics::VertexNeighbours(mesh);
  std::vector<bool> on_boundary(mesh.num_vertices(), false);
  const physics::Triangles adjacency = physics::TriangleAdjacency(mesh);
  for (int f = 0; f < mesh.num_triangles(); ++f) {
    for (int k = 0; k < 3; ++k) {
      if (adjacency(f, k) < 0) on_boundary[mesh.triangles(f, k)] = on_boundary[mesh.triangles(f, (k + 1) % 3)] = true;
    }
  }
  for (int it = 0; it < iterations; ++it) {
    const physics::Vertices previous = mesh.vertices;  // Jacobi update: order-independent
    for (int i = 0; i < mesh.num_vertices(); ++i) {
      if (on_boundary[i] || neighbours[i].empty()) continue;
      const Eigen::Vector3d p = previous.row(i);
      Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
      for (int j : neighbours[i]) centroid += previous.row(j).transpose();
      centroid /= static_cast<double>(neighbours[i].size());
      const Eigen::Vector3d n = Gradient(field, p).normalized();
      Eigen::Vector3d move = centroid - p;
      move -= move.dot(n) * n;
      mesh.vertices.row(i) = ProjectOntoZeroSet(field, p + 0.5 * move).transpose();
    }
  }
}

}  // namespace vesica::app::anatomy
