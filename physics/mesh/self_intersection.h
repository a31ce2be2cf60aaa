#pragma once
// Finds the pairs of triangles of a surface that cross each other (triangle_crossing.h), e.g. the
// 16 pairs of a liver surface whose smoothing pushed folds through the opposite side. A closed
// surface that intersects itself encloses no well-defined volume: BEM and collision need one.

#include <utility>
#include <vector>

#include "physics/mesh/triangle_mesh.h"

namespace vesica::physics {

/// Every crossing pair (f, g) of rows of mesh.triangles (indices in range), f < g, sorted.
/// Candidates come from a sweep over the triangles' bounding boxes along the mesh's longest axis:
/// about n log n for an organ surface.
std::vector<std::pair<int, int>> SelfIntersections(const TriangleMesh& mesh);

}  // namespace vesica::physics
