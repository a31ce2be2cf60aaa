#pragma once
// Analytic meshes for tests, validation and benchmarks: structured tet boxes and icospheres.

#include "physics/mesh/tetrahedral_mesh.h"
#include "physics/mesh/triangle_mesh.h"

namespace vesica::physics {

/// A box [0, size.x] x [0, size.y] x [0, size.z] split into cells.x * cells.y * cells.z hexahedra,
/// each cut into 6 positive tets sharing the main diagonal (Kuhn subdivision, conforming).
/// Vertex (i, j, k) has index i + (cells.x + 1) * (j + (cells.y + 1) * k).
TetrahedralMesh MakeBoxTetMesh(const Eigen::Vector3d& size, const Eigen::Vector3i& cells);

/// A sphere of the given radius centred at the origin: an icosahedron subdivided `levels` times
/// (10 * 4^levels + 2 vertices), outward-oriented.
TriangleMesh MakeIcosphere(double radius, int levels);

}  // namespace vesica::physics
