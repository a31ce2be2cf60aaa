#pragma once
// A label map on a regular voxel grid, as physics sees a segmented CT (seed section 3.3): no VTK
// here, app/patient fills it from NIfTI or DICOM. Voxel (i, j, k) has its centre at
// origin_m + direction * (i dx, j dy, k dz), in the world frame (x left, y anterior, z cranial).

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

namespace vesica::physics {

struct LabelVolume {
  std::array<int, 3> dims{0, 0, 0};                         ///< voxels along i, j, k
  Eigen::Vector3d spacing_m = Eigen::Vector3d::Ones();      ///< voxel size, > 0
  Eigen::Vector3d origin_m = Eigen::Vector3d::Zero();       ///< centre of voxel (0, 0, 0)
  Eigen::Matrix3d direction = Eigen::Matrix3d::Identity();  ///< columns: i, j, k axes in the world (orthonormal)
  std::vector<std::uint8_t> labels;                         ///< dims[0] * dims[1] * dims[2], i fastest

  [[nodiscard]] std::size_t Index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(dims[0]) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(dims[1]) * k);
  }
  [[nodiscard]] std::uint8_t At(int i, int j, int k) const { return labels[Index(i, j, k)]; }
  [[nodiscard]] Eigen::Vector3d Position(int i, int j, int k) const {
    return origin_m + direction * Eigen::Vector3d(i * spacing_m.x(), j * spacing_m.y(), k * spacing_m.z());
  }
  [[nodiscard]] double VoxelVolume_m3() const { return spacing_m.prod(); }
};

}  // namespace vesica::physics
