#pragma once
// Improves the triangle shapes of a decimated surface before tetrahedralisation: Delaunay edge
// flips between nearly coplanar triangles, then vertices slide towards their neighbours'
// centroid within the tangent plane and are projected back onto the shape's zero set.

#include "app/anatomy/implicit_surface.h"
#include "physics/mesh/triangle_mesh.h"

namespace vesica::app::anatomy {

/// `iterations` rounds of flips, tangential relaxation and projection (Newton steps on `field`).
/// Boundary vertices of open surfaces do not move.
void RelaxOntoField(physics::TriangleMesh& mesh, const ImplicitField& field, int iterations);

}  // namespace vesica::app::anatomy
