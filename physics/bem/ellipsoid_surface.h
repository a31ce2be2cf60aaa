#pragma once
// Closed ellipsoid surfaces with an exact vertex count, for BEM validation and benchmarks (the
// paper's 95 / 296 / 752-node livers). Belongs with physics/mesh/primitives.h; kept here until
// that folder's owner takes it.

#include "physics/mesh/triangle_mesh.h"

namespace vesica::physics {

/// Ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1 (semi_axes = a, b, c in metres) with exactly
/// `num_vertices` vertices (>= 8): two poles on z and latitude rings whose vertex counts follow
/// the ring circumference, zipped into triangles; closed and outward-oriented.
TriangleMesh MakeEllipsoidSurface(const Eigen::Vector3d& semi_axes, int num_vertices);

}  // namespace vesica::physics
