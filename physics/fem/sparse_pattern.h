#pragma once
// The 3x3-block sparsity of a tet mesh's stiffness/mass matrices, with each tet's block slots
// precomputed so that per-step assembly writes straight into the value array (no triplets, no
// search). Column-major, full (both triangles): identical arrays read as row-major.

#include <array>
#include <vector>

#include <Eigen/SparseCore>

#include "physics/mesh/tetrahedral_mesh.h"

namespace vesica::physics {

struct SparsePattern {
  /// 3n x 3n structure, values zero.
  Eigen::SparseMatrix<double> structure;
  /// Per tet, per block (a, b) (index 4a + b): value index of entry (3 node_a, 3 node_b).
  std::vector<std::array<int, 16>> block_slot;
  /// Per node: distance in the value array between consecutive columns of one block (3 degree).
  std::vector<int> column_stride;
  /// Per dof: value index of its diagonal entry.
  std::vector<int> diagonal_slot;

  /// Value index of entry (r, c) of block (a, b) of tet t; node_b = tets(t, b).
  int Slot(int t, int a, int b, int node_b, int r, int c) const {
    return block_slot[t][4 * a + b] + c * column_stride[node_b] + r;
  }
};

SparsePattern BuildSparsePattern(const TetrahedralMesh& mesh);

}  // namespace vesica::physics
