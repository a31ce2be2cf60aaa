#include "physics/fem/quadratic_tet_mesh.h"

#include <vector>

namespace vesica::physics {

QuadraticTetMesh MakeQuadraticTetMesh(const TetrahedralMesh& mesh) {
  QuadraticTetMesh out;
  out.num_corners = mesh.num_vertices();
  out.tets.resize(mesh.num_tets(), 10);
  std::vector<Eigen::RowVector3d> midpoints;
  for (int t = 0; t < mesh.num_tets(); ++t) {
    for (int k = 0; k < 4; ++k) out.tets(t, k) = mesh.tets(t, k);
    for (int e = 0; e < 6; ++e) {
      const int a = mesh.tets(t, kTet10Edges[e][0]), b = mesh.tets(t, kTet10Edges[e][1]);
      const auto [it, added] =
          out.edge_midpoints.try_emplace(std::minmax(a, b), out.num_corners + static_cast<int>(midpoints.size()));
      if (added) midpoints.push_back(0.5 * (mesh.vertices.row(a) + mesh.vertices.row(b)));
      out.tets(t, 4 + e) = it->second;
    }
  }
  out.nodes.resize(out.num_corners + static_cast<Eigen::Index>(midpoints.size()), 3);
  out.nodes.topRows(out.num_corners) = mesh.vertices;
  for (size_t i = 0; i < midpoints.size(); ++i)
    out.nodes.row(out.num_corners + static_cast<Eigen::Index>(i)) = midpoints[i];
  return out;
}

}  // namespace vesica::physics
