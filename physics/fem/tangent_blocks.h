#pragma once
// The corotational tangent assembled node pair by node pair (gather) instead of tet by tet
// (scatter). Per tet the blocks are R K_ab R^T = V (lambda r_a r_b^T + mu r_b r_a^T +
// mu (g_a . g_b) I) with r_a = R g_a; summed over the tets that share nodes a and b this is
// lambda B + mu B^T + d I with B = sum V r_a r_b^T and d = sum mu V g_a . g_b, which does not turn
// (built once here). So each pattern block is computed in registers from its tets' scaled turned
// gradients w_a = sqrt(V) r_a (B = sum w_a w_b^T) and written once, its transpose with it: no
// read-modify-write of 16 blocks a tet, no zeroing of the values first.

#include <vector>

#include "physics/fem/sparse_pattern.h"
#include "physics/fem/tet_element.h"
#include "physics/mesh/tetrahedral_mesh.h"

namespace vesica::physics {

/// Doubles per tet in the corner-vector array the tangent is assembled from: w_0..w_3, x y z and a
/// zero pad each.
inline constexpr int kCornerVectorFields = 16;

struct TangentBlocks {
  /// Pair p is the block of row node a and column node b, a <= b (pattern value index slot_ab[p] of
  /// its entry (3a, 3b), column stride stride_b[p]) and, when a != b, its transpose (slot_ba[p],
  /// stride_a[p]). Pairs are in the order of slot_ab: column by column through the values.
  std::vector<int> slot_ab, stride_b, slot_ba, stride_a;
  /// d of the pair (N/m): sum over its tets of mu V g_a . g_b.
  std::vector<double> shear_diagonal;
  /// The pair's tets [pair_begin[p], pair_begin[p + 1]): offsets into the corner-vector array of
  /// the tet's w_a and w_b (kCornerVectorFields t + 4 corner).
  std::vector<int> pair_begin, corner_a, corner_b;

  int num_pairs() const { return static_cast<int>(slot_ab.size()); }
};

/// Pairs of every block of the pattern (the diagonal block of a node in no tet too: d = 0, no tets).
TangentBlocks BuildTangentBlocks(const TetrahedralMesh& mesh, const SparsePattern& pattern,
                                 const std::vector<TetElement>& elements, double mu_Pa);

}  // namespace vesica::physics
