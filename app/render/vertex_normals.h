#pragma once
// Per-vertex normals of a deforming triangle mesh, recomputed every frame. No VTK.

#include "physics/mesh/mesh_types.h"

namespace vesica::app {

/// @param[in] V #V by 3 vertex positions
/// @param[in] F #F by 3 triangles into V (indices assumed valid)
/// @return #V by 3 unit normals: the area-weighted sum of the incident triangles' normals
///   (unit z where that sum vanishes). O(#F), no allocation beyond the result; measured far
///   cheaper per frame than re-running vtkPolyDataNormals (see laparoscope_view.cpp).
physics::Vertices VertexNormals(const physics::Vertices& V, const physics::Triangles& F);

}  // namespace vesica::app
