#include "physics/fem/tangent_blocks.h"

#include <cstddef>

namespace vesica::physics {

TangentBlocks BuildTangentBlocks(const TetrahedralMesh& mesh, const SparsePattern& pattern,
                                 const std::vector<TetElement>& elements, double mu_Pa) {
  // A pair is known by the value index of its entry (3a, 3b), a <= b; listing the pairs in that
  // order is a counting sort over the values (no comparison sort of ~10 entries a tet).
  const std::size_t nnz = static_cast<std::size_t>(pattern.structure.nonZeros());
  auto each_corner_pair = [&](auto&& visit) {
    for (int t = 0; t < mesh.num_tets(); ++t)
      for (int ca = 0; ca < 4; ++ca)
        for (int cb = 0; cb < 4; ++cb) {
          const int na = mesh.tets(t, ca), nb = mesh.tets(t, cb);
          if (na < nb || (na == nb && ca == cb)) visit(t, ca, cb, na, nb);
        }
  };
  std::vector<int> count(nnz + 1, -1);  // -1: no pair at this value index
  for (int n = 0; n < mesh.num_vertices(); ++n)
    count[pattern.diagonal_slot[3 * static_cast<std::size_t>(n)]] = 0;  // a node in no tet too
  each_corner_pair([&](int t, int ca, int cb, int, int) {
    int& c = count[pattern.block_slot[t][4 * ca + cb]];
    c = c < 0 ? 1 : c + 1;
  });

  TangentBlocks blocks;
  std::vector<int> pair_of_slot(nnz, -1);
  blocks.pair_begin.push_back(0);
  for (std::size_t slot = 0; slot < nnz; ++slot) {
    if (count[slot] < 0) continue;
    pair_of_slot[slot] = blocks.num_pairs();
    blocks.slot_ab.push_back(static_cast<int>(slot));
    blocks.pair_begin.push_back(blocks.pair_begin.back() + count[slot]);
  }
  const int pairs = blocks.num_pairs();
  blocks.slot_ba.assign(pairs, -1);
  blocks.stride_a.assign(pairs, 0);
  blocks.stride_b.assign(pairs, 0);
  blocks.shear_diagonal.assign(pairs, 0.0);
  for (int n = 0; n < mesh.num_vertices(); ++n) {
    const int p = pair_of_slot[pattern.diagonal_slot[3 * static_cast<std::size_t>(n)]];
    blocks.slot_ba[p] = blocks.slot_ab[p];
    blocks.stride_a[p] = blocks.stride_b[p] = pattern.column_stride[n];
  }
  blocks.corner_a.resize(blocks.pair_begin.back());
  blocks.corner_b.resize(blocks.pair_begin.back());
  std::vector<int> next(blocks.pair_begin.begin(), blocks.pair_begin.end() - 1);
  each_corner_pair([&](int t, int ca, int cb, int na, int nb) {
    const int p = pair_of_slot[pattern.block_slot[t][4 * ca + cb]];
    const int k = next[p]++;
    blocks.corner_a[k] = kCornerVectorFields * t + 4 * ca;
    blocks.corner_b[k] = kCornerVectorFields * t + 4 * cb;
    const TetElement& e = elements[t];
    blocks.shear_diagonal[p] += mu_Pa * e.rest_volume_m3 * e.shape_gradients[ca].dot(e.shape_gradients[cb]);
    blocks.slot_ba[p] = pattern.block_slot[t][4 * cb + ca];
    blocks.stride_a[p] = pattern.column_stride[na];
    blocks.stride_b[p] = pattern.column_stride[nb];
  });
  return blocks;
}

}  // namespace vesica::physics
