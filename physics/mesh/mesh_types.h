#pragma once
// Storage types shared by every mesh in physics/: row-major so that vertex i is contiguous and the
// whole array maps onto a 3n vector of nodal unknowns without a copy.

#include <Eigen/Core>

namespace vesica::physics {

/// #V by 3 vertex positions in metres (one row a vertex).
using Vertices = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// #F by 3 vertex indices of triangles, counter-clockwise seen from outside (normal outward).
using Triangles = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// #T by 4 vertex indices of tetrahedra, ordered so that the signed volume is positive.
using Tetrahedra = Eigen::Matrix<int, Eigen::Dynamic, 4, Eigen::RowMajor>;

/// Maps a Vertices array onto the stacked 3n vector (x0 y0 z0 x1 ...), no copy.
inline Eigen::Map<Eigen::VectorXd> AsStackedVector(Vertices& v) {
  return {v.data(), v.size()};
}
inline Eigen::Map<const Eigen::VectorXd> AsStackedVector(const Vertices& v) {
  return {v.data(), v.size()};
}

}  // namespace vesica::physics
