#pragma once
// Rest data of a mesh's tets in structure-of-arrays blocks for the SIMD element pass
// (element_pass_simd.h): one block holds kElementBatchWidth tets lane by lane, so a kernel loads
// one field of 8 (AVX-512) or 4 (AVX2) consecutive tets with one vector load.

#include <vector>

#include "physics/fem/huge_page_allocator.h"
#include "physics/fem/tet_element.h"
#include "physics/mesh/tetrahedral_mesh.h"

namespace vesica::physics {

/// Tets per block (the widest vector, 8 doubles); narrower kernels read half a block at a time.
inline constexpr int kElementBatchWidth = 8;
/// Fields per block: grad N1, N2, N3 (x y z each, 1/m; grad N0 = -(sum of the others)) and the
/// rest volume (m^3).
inline constexpr int kElementBatchFields = 10;
/// Fields per block of the turned gradients R grad N1, N2, N3 a corotational pass can leave for the
/// tangent products that follow it (elastic_forces.h).
inline constexpr int kTurnedGradientFields = 9;

struct ElementBatches {
  int num_tets = 0;
  /// [block][field][lane]; lanes past num_tets in the last block are zero (volume 0).
  HugePageVector<double> rest;
  /// [block][corner][lane]: 3 x node index of each corner (its x dof; gather index into u);
  /// padding lanes repeat node 0 of tet 0.
  HugePageVector<int> dofs;

  /// Rest volume of tet t (m^3), from the compact blocks (TetElement is 176 bytes a tet: reading
  /// one double of each misses the cache for every tet).
  double rest_volume_m3(int t) const {
    return rest[static_cast<size_t>(t / kElementBatchWidth) * kElementBatchFields * kElementBatchWidth +
                9 * kElementBatchWidth + t % kElementBatchWidth];
  }
};

/// Copies the elements' gradients and volumes into blocks. elements[t] belongs to mesh tet t.
ElementBatches BuildElementBatches(const TetrahedralMesh& mesh, const std::vector<TetElement>& elements);

}  // namespace vesica::physics
