#pragma once
// Quadratic (10-node) tets on a linear tet mesh (issue 37): each tet's corners are the mesh's
// vertices (same numbers), and one node at the midpoint of every edge is added after them, so the
// geometry stays the linear mesh's (straight edges) and only the displacement becomes quadratic.

#include <Eigen/Core>
#include <map>
#include <utility>

#include "physics/mesh/tetrahedral_mesh.h"

namespace vesica::physics {

/// Local order of a 10-node tet: corners 0-3, then the midpoints of the edges in kTet10Edges.
inline constexpr int kTet10Edges[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};

struct QuadraticTetMesh {
  Vertices nodes;                                                ///< #N by 3, metres: the corners, then the midpoints
  Eigen::Matrix<int, Eigen::Dynamic, 10, Eigen::RowMajor> tets;  ///< #T by 10, in the local order above
  int num_corners = 0;                                           ///< the linear mesh's vertex count
  std::map<std::pair<int, int>, int> edge_midpoints;             ///< (smaller, larger corner) -> midpoint node

  int num_nodes() const { return static_cast<int>(nodes.rows()); }
  /// The midpoint node of the edge between corners a and b; throws std::out_of_range if no tet has it.
  int Midpoint(int a, int b) const { return edge_midpoints.at(std::minmax(a, b)); }
};

QuadraticTetMesh MakeQuadraticTetMesh(const TetrahedralMesh& mesh);

}  // namespace vesica::physics
