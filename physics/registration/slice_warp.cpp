#include "physics/registration/slice_warp.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "physics/mesh/barycentric.h"

namespace vesica::physics {

namespace {
// Continuous voxel index of a world point.
Eigen::Vector3d VoxelIndex(const LabelVolume& grid, const Eigen::Vector3d& p_W) {
  return (grid.direction.transpose() * (p_W - grid.origin_m)).cwiseQuotient(grid.spacing_m);
}
}  // namespace

double SampleTrilinear(const LabelVolume& grid, const std::vector<std::int16_t>& ct, const Eigen::Vector3d& index) {
  std::array<int, 3> base{};
  std::array<double, 3> frac{};
  for (int d = 0; d < 3; ++d) {
    const double c = std::clamp(index[d], 0.0, static_cast<double>(grid.dims[static_cast<size_t>(d)] - 1));
    base[static_cast<size_t>(d)] =
        std::min(static_cast<int>(std::floor(c)), std::max(grid.dims[static_cast<size_t>(d)] - 2, 0));
    frac[static_cast<size_t>(d)] = c - base[static_cast<size_t>(d)];
  }
  double value = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    double weight = 1.0;
    std::array<int, 3> at{};
    for (int d = 0; d < 3; ++d) {
      const int bit = (corner >> d) & 1;
      const size_t sd = static_cast<size_t>(d);
      at[sd] = std::min(base[sd] + bit, grid.dims[sd] - 1);
      weight *= bit ? frac[sd] : 1.0 - frac[sd];
    }
    if (weight != 0.0) value += weight * ct[grid.Index(at[0], at[1], at[2])];
  }
  return value;
}

WarpedSlice WarpSlice(const LabelVolume& grid, const std::vector<std::int16_t>& ct, const TetrahedralMesh& rest,
                      const Vertices& deformed, SliceAxis axis, int index) {
  const size_t voxels = static_cast<size_t>(grid.dims[0]) * grid.dims[1] * grid.dims[2];
  if (ct.size() != voxels)
    throw std::invalid_argument("WarpSlice: the CT has " + std::to_string(ct.size()) + " values, its grid " +
                                std::to_string(voxels));
  if (deformed.rows() != rest.vertices.rows())
    throw std::invalid_argument("WarpSlice: " + std::to_string(deformed.rows()) + " deformed positions for a mesh of " +
                                std::to_string(rest.vertices.rows()) + " nodes");
  const int normal_axis = static_cast<int>(axis);
  if (index < 0 || index >= grid.dims[static_cast<size_t>(normal_axis)])
    throw std::invalid_argument("WarpSlice: slice " + std::to_string(index) + " outside 0.." +
                                std::to_string(grid.dims[static_cast<size_t>(normal_axis)] - 1));
  const int axis_a = normal_axis == 0 ? 1 : 0;
  const int axis_b = normal_axis == 2 ? 1 : 2;
  WarpedSlice out;
  out.axis = axis;
  out.index = index;
  out.dims = {grid.dims[static_cast<size_t>(axis_a)], grid.dims[static_cast<size_t>(axis_b)]};
  const size_t pixels = static_cast<size_t>(out.dims[0]) * out.dims[1];
  out.values.resize(pixels);
  out.in_mesh.assign(pixels, 0);
  auto voxel = [&](int a, int b) {
    std::array<int, 3> ijk{};
    ijk[static_cast<size_t>(normal_axis)] = index;
    ijk[static_cast<size_t>(axis_a)] = a;
    ijk[static_cast<size_t>(axis_b)] = b;
    return ijk;
  };
  for (int b = 0; b < out.dims[1]; ++b)
    for (int a = 0; a < out.dims[0]; ++a) {
      const auto ijk = voxel(a, b);
      out.values[static_cast<size_t>(a) + static_cast<size_t>(out.dims[0]) * b] =
          ct[grid.Index(ijk[0], ijk[1], ijk[2])];
    }
  // Tet by tet over the pixels its bounding box covers in the slice.
  for (int t = 0; t < rest.num_tets(); ++t) {
    std::array<Eigen::Vector3d, 4> x;
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = Eigen::Vector3d::Constant(-1e300);
    for (int k = 0; k < 4; ++k) {
      x[static_cast<size_t>(k)] = deformed.row(rest.tets(t, k)).transpose();
      const Eigen::Vector3d c = VoxelIndex(grid, x[static_cast<size_t>(k)]);
      lo = lo.cwiseMin(c);
      hi = hi.cwiseMax(c);
    }
    if (index < lo[normal_axis] || index > hi[normal_axis]) continue;
    const int a0 = std::max(0, static_cast<int>(std::ceil(lo[axis_a])));
    const int a1 = std::min(out.dims[0] - 1, static_cast<int>(std::floor(hi[axis_a])));
    const int b0 = std::max(0, static_cast<int>(std::ceil(lo[axis_b])));
    const int b1 = std::min(out.dims[1] - 1, static_cast<int>(std::floor(hi[axis_b])));
    for (int b = b0; b <= b1; ++b)
      for (int a = a0; a <= a1; ++a) {
        const size_t pixel = static_cast<size_t>(a) + static_cast<size_t>(out.dims[0]) * b;
        if (out.in_mesh[pixel]) continue;  // a shared face: the first tet decided
        const auto ijk = voxel(a, b);
        const Eigen::Vector3d p = grid.Position(ijk[0], ijk[1], ijk[2]);
        const Eigen::Vector4d w = TetBarycentric(p, x[0], x[1], x[2], x[3]);
        if (w.minCoeff() < -1e-12) continue;
        Eigen::Vector3d rest_point = Eigen::Vector3d::Zero();
        for (int k = 0; k < 4; ++k) rest_point += w[k] * rest.vertices.row(rest.tets(t, k)).transpose();
        out.values[pixel] = static_cast<std::int16_t>(
            std::lround(std::clamp(SampleTrilinear(grid, ct, VoxelIndex(grid, rest_point)), -32768.0, 32767.0)));
        out.in_mesh[pixel] = 1;
      }
  }
  return out;
}

}  // namespace vesica::physics
