#pragma once
// Graded, conforming refinement of a BEM surface toward a tool's contact (issue 37): triangles
// with a corner near the contact are split 1:4 (red); a neighbour left with one split edge is
// halved (green), one with two or three is split red too, so no node hangs. The geometry is kept
// exactly (new vertices are edge midpoints), and the old vertices keep their indices, so fields on
// the refined surface compare vertex by vertex with the original. tools/convergence/reference.py
// grades the CalculiX reference the same way.

#include <Eigen/Core>
#include <span>

#include "physics/mesh/triangle_mesh.h"

namespace vesica::physics {

struct RefinedSurface {
  TriangleMesh surface;             ///< the original #V vertices first, then the edge midpoints
  Eigen::VectorXi parent_triangle;  ///< #F: the original triangle each new triangle lies in
};

/// One pass per radius (m): triangles with a corner within the radius of `centre_m` are split.
/// A midpoint is labelled with the bits its two end vertices share (a fixed region stays fixed).
/// Throws MeshError when a radius is not positive and finite.
RefinedSurface RefineTowardPoint(const TriangleMesh& surface, const Eigen::Vector3d& centre_m,
                                 std::span<const double> radii_m);

/// The same toward a region: a triangle is split when a corner lies within the radius of any of
/// `centres_m` (k x 3), e.g. the gallbladder bed's vertices, where the tools work.
RefinedSurface RefineTowardPoints(const TriangleMesh& surface, const Vertices& centres_m,
                                  std::span<const double> radii_m);

}  // namespace vesica::physics
