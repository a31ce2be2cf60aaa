#pragma once
// An axis-aligned box in the display frame (display_frame.h), laid out as VTK's bounds: xmin,
// xmax, ymin, ymax, zmin, zmax (internal to app/render). The view sets the camera's clipping
// range from the box of what it draws, gathered from what it already knows (the organs' points
// as it writes them, the static context's box once) rather than VTK asking each actor's
// pipeline for its bounds every frame.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <limits>

namespace vesica::app {

struct DisplayBounds {
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  std::array<double, 6> box{kInf, -kInf, kInf, -kInf, kInf, -kInf};  // empty

  bool empty() const { return box[0] > box[1]; }
  void Extend(double x, double y, double z) {
    const double p[3] = {x, y, z};
    for (int c = 0; c < 3; ++c) {
      box[2 * c] = std::min(box[2 * c], p[c]);
      box[2 * c + 1] = std::max(box[2 * c + 1], p[c]);
    }
  }
  void Extend(const Eigen::Vector3d& p_D) { Extend(p_D.x(), p_D.y(), p_D.z()); }
  /// VTK's bounds (null, or uninitialised with min > max, for an empty actor: ignored).
  void Extend(const double* vtk_bounds) {
    if (vtk_bounds == nullptr || vtk_bounds[0] > vtk_bounds[1]) return;
    Extend(vtk_bounds[0], vtk_bounds[2], vtk_bounds[4]);
    Extend(vtk_bounds[1], vtk_bounds[3], vtk_bounds[5]);
  }
  void Extend(const DisplayBounds& other) {
    if (!other.empty()) Extend(other.box.data());
  }
};

}  // namespace vesica::app
