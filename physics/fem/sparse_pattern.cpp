#include "physics/fem/sparse_pattern.h"

#include <algorithm>

namespace vesica::physics {

SparsePattern BuildSparsePattern(const TetrahedralMesh& mesh) {
  const int n = mesh.num_vertices();
  std::vector<std::vector<int>> neighbours(n);
  for (int t = 0; t < mesh.num_tets(); ++t)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) neighbours[mesh.tets(t, b)].push_back(mesh.tets(t, a));
  for (int i = 0; i < n; ++i) {
    neighbours[i].push_back(i);  // isolated nodes still get a diagonal
    std::sort(neighbours[i].begin(), neighbours[i].end());
    neighbours[i].erase(std::unique(neighbours[i].begin(), neighbours[i].end()), neighbours[i].end());
  }

  SparsePattern p;
  p.column_stride.resize(n);
  std::vector<int> node_base(n);
  long long nnz = 0;
  for (int b = 0; b < n; ++b) {
    node_base[b] = static_cast<int>(nnz);
    p.column_stride[b] = 3 * static_cast<int>(neighbours[b].size());
    nnz += 9LL * static_cast<long long>(neighbours[b].size());
  }
  p.structure.resize(3 * n, 3 * n);
  p.structure.resizeNonZeros(static_cast<Eigen::Index>(nnz));
  int* outer = p.structure.outerIndexPtr();
  int* inner = p.structure.innerIndexPtr();
  p.diagonal_slot.resize(3 * n);
  for (int b = 0; b < n; ++b) {
    const auto& nb = neighbours[b];
    for (int c = 0; c < 3; ++c) {
      int slot = node_base[b] + c * p.column_stride[b];
      outer[3 * b + c] = slot;
      for (int a : nb)
        for (int r = 0; r < 3; ++r) {
          if (a == b && r == c) p.diagonal_slot[3 * b + c] = slot;
          inner[slot++] = 3 * a + r;
        }
    }
  }
  outer[3 * n] = static_cast<int>(nnz);
  std::fill(p.structure.valuePtr(), p.structure.valuePtr() + nnz, 0.0);

  p.block_slot.resize(mesh.num_tets());
  for (int t = 0; t < mesh.num_tets(); ++t)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        const int na = mesh.tets(t, a), nb = mesh.tets(t, b);
        const auto& list = neighbours[nb];
        const int pos = static_cast<int>(std::lower_bound(list.begin(), list.end(), na) - list.begin());
        p.block_slot[t][4 * a + b] = node_base[nb] + 3 * pos;
      }
  return p;
}

}  // namespace vesica::physics
