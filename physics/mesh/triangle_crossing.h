#pragma once
// Whether two triangles of one surface cross each other: the test behind the self-intersection
// check (self_intersection.h). Triangles of a surface meet where they share vertices; that is not
// a crossing. What is:
//   - no shared vertex: the triangles have a point in common (an edge of one passes through the
//     other, or, in one plane, their interiors overlap);
//   - one shared vertex: they have more than that vertex in common;
//   - a shared edge: the two lie in one plane on the same side of the edge (a folded face);
//   - three shared vertices: the same triangle twice.
// Touching without passing through (a vertex resting on the other triangle, within a relative
// 1e-9 of the triangles' size) is not counted: a valid surface must never be refused, and a real
// crossing passes through by a margin.

#include "physics/mesh/triangle_mesh.h"

namespace vesica::physics {

/// Triangles f and g (rows of mesh.triangles, indices in range) cross as above.
bool TrianglesCross(const TriangleMesh& mesh, int f, int g);

}  // namespace vesica::physics
