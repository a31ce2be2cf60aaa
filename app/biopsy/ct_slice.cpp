#include "app/biopsy/ct_slice.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace vesica::app::biopsy {

SlicePlane AxialSliceThrough(const Eigen::Vector3d& p_W, double pixel_m, int size) {
  SlicePlane plane;
  plane.centre_W = p_W;
  plane.column_W = Eigen::Vector3d::UnitX();
  plane.row_W = -Eigen::Vector3d::UnitY();
  plane.pixel_m = pixel_m;
  plane.columns = plane.rows = size;
  return plane;
}

SlicePlane ObliqueSliceAlong(const physics::NeedlePose& pose, double pixel_m, int size) {
  SlicePlane plane;
  const Eigen::Vector3d d = pose.direction.normalized();
  plane.centre_W = pose.tip_m;
  plane.column_W = d;
  // The axis across the needle nearest to posterior; for a needle along y, nearest to caudal.
  Eigen::Vector3d across = -Eigen::Vector3d::UnitY() - d * (-d.y());
  if (across.norm() < 0.3) across = -Eigen::Vector3d::UnitZ() - d * (-d.z());
  plane.row_W = across.normalized();
  plane.pixel_m = pixel_m;
  plane.columns = plane.rows = size;
  return plane;
}

Eigen::Vector3d PixelCentre(const SlicePlane& plane, int column, int row) {
  const double c = (column + 0.5 - 0.5 * plane.columns) * plane.pixel_m;
  const double r = (row + 0.5 - 0.5 * plane.rows) * plane.pixel_m;
  return plane.centre_W + c * plane.column_W + r * plane.row_W;
}

SlicePoint ProjectOntoSlice(const SlicePlane& plane, const Eigen::Vector3d& p_W) {
  const Eigen::Vector3d offset = p_W - plane.centre_W;
  SlicePoint point;
  point.pixel = {offset.dot(plane.column_W) / plane.pixel_m + 0.5 * plane.columns,
                 offset.dot(plane.row_W) / plane.pixel_m + 0.5 * plane.rows};
  point.off_plane_m = offset.dot(plane.column_W.cross(plane.row_W));
  return point;
}

std::vector<float> SampleSlice(const physics::DeformedCt& ct, const SlicePlane& plane) {
  std::vector<float> hu(static_cast<std::size_t>(plane.columns) * static_cast<std::size_t>(plane.rows));
  for (int row = 0; row < plane.rows; ++row)
    for (int column = 0; column < plane.columns; ++column)
      hu[static_cast<std::size_t>(row) * static_cast<std::size_t>(plane.columns) + static_cast<std::size_t>(column)] =
          static_cast<float>(ct.Sample(PixelCentre(plane, column, row)).hu);
  return hu;
}

unsigned char WindowHu(float hu, double level, double width) {
  const double grey = (static_cast<double>(hu) - (level - 0.5 * width)) / width * 255.0;
  return static_cast<unsigned char>(std::lround(std::clamp(grey, 0.0, 255.0)));
}

}  // namespace vesica::app::biopsy
