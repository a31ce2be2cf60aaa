#pragma once
// Improves the triangle shapes of a decimated surface before tetrahedralisation: Delaunay edge
// flips between nearly coplanar triangles, then vertices slide towards their neighbours'
// centroid within the tangent plane and are projected back onto the shape's zero set.

#include "app/anatomy/implicit_surface.h"
#include "physics/mesh/triangle_mesh.h"

namespace vesica::app::anatomy {

/// `iterations` rounds of flips, tangential relaxation and projection (Newton steps on `field`).
/// Boundary vertices of open surfaces do not move. With `edge_length_m` (metres, > 0 at every
/// point; empty: uniform) the mesh is graded: each vertex moves toward its neighbours' centroid
/// weighted by 1 / edge_length_m, so that edges come out shorter where it is smaller (a sharp
/// crest drawn smooth with the same vertex count).
void RelaxOntoField(physics::TriangleMesh& mesh, const ImplicitField& field, int iterations,
                    const ImplicitField& edge_length_m = {});

}  // namespace vesica::app::anatomy
