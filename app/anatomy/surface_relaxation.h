#pragma once
// Improves the triangle shapes of a decimated surface before tetrahedralisation: vertices slide
// towards their neighbours' centroid within the tangent plane, then are projected back onto the
// shape's zero set. Connectivity is unchanged; the surface stays on the exact implicit shape.

#include "app/anatomy/implicit_surface.h"
#include "physics/mesh/triangle_mesh.h"

namespace vesica::app::anatomy {

/// `iterations` rounds of tangential relaxation plus projection (Newton steps on `field`).
/// Boundary vertices of open surfaces do not move.
void RelaxOntoField(physics::TriangleMesh& mesh, const ImplicitField& field, int iterations);

}  // namespace vesica::app::anatomy
