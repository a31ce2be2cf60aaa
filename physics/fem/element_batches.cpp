#include "physics/fem/element_batches.h"

namespace vesica::physics {

ElementBatches BuildElementBatches(const TetrahedralMesh& mesh, const std::vector<TetElement>& elements) {
  constexpr int w = kElementBatchWidth;
  ElementBatches b;
  b.num_tets = mesh.num_tets();
  const int blocks = (b.num_tets + w - 1) / w;
  b.rest.assign(static_cast<size_t>(blocks) * kElementBatchFields * w, 0.0);
  b.dofs.assign(static_cast<size_t>(blocks) * 4 * w, b.num_tets > 0 ? 3 * mesh.tets(0, 0) : 0);
  for (int t = 0; t < b.num_tets; ++t) {
    const int block = t / w, lane = t % w;
    double* rest = b.rest.data() + static_cast<size_t>(block) * kElementBatchFields * w + lane;
    const TetElement& e = elements[t];
    for (int a = 1; a < 4; ++a)
      for (int c = 0; c < 3; ++c) rest[(3 * (a - 1) + c) * w] = e.shape_gradients[a][c];
    rest[9 * w] = e.rest_volume_m3;
    int* dofs = b.dofs.data() + static_cast<size_t>(block) * 4 * w + lane;
    for (int a = 0; a < 4; ++a) dofs[a * w] = 3 * mesh.tets(t, a);
  }
  return b;
}

}  // namespace vesica::physics
