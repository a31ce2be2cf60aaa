#pragma once
// Warping a CT slice with the registration's displacement field (seed section 4's validation):
// a voxel of the slice that lies in the deformed mesh takes the value the CT has where that
// material point was at rest (x = X + u(X) inverted tet by tet, trilinear sampling); a voxel
// outside the mesh keeps its value (the field is only known inside the organ).

#include <array>
#include <cstdint>
#include <vector>

#include "physics/mesh/tetrahedral_mesh.h"
#include "physics/patient/label_volume.h"

namespace vesica::physics {

enum class SliceAxis { kI = 0, kJ = 1, kK = 2 };

/// A slice of the volume's grid normal to `axis` at `index`; pixel (a, b) is the voxel whose
/// other two indices, in order i, j, k without `axis`, are a and b; a fastest.
struct WarpedSlice {
  SliceAxis axis = SliceAxis::kK;
  int index = 0;
  std::array<int, 2> dims{0, 0};
  std::vector<std::int16_t> values;   ///< warped CT (HU)
  std::vector<std::uint8_t> in_mesh;  ///< 1 where the pixel lies in the deformed mesh
};

/// `grid`: the CT's grid (its labels are not read); `ct`: its values, i fastest. `deformed`: the
/// mesh's positions (#V by 3) after registration, `rest` the mesh at the CT's time. Throws
/// std::invalid_argument for sizes that do not match or an index outside the grid.
WarpedSlice WarpSlice(const LabelVolume& grid, const std::vector<std::int16_t>& ct, const TetrahedralMesh& rest,
                      const Vertices& deformed, SliceAxis axis, int index);

/// Trilinear value of the volume at a continuous voxel index (clamped to the grid).
double SampleTrilinear(const LabelVolume& grid, const std::vector<std::int16_t>& ct, const Eigen::Vector3d& index);

}  // namespace vesica::physics
