#pragma once
// Brute-force point and ray queries against a triangle mesh: for the generator's port placement
// and the anatomy tests (a few thousand triangles, so no acceleration structure).

#include <Eigen/Core>
#include <optional>

#include "physics/mesh/triangle_mesh.h"

namespace vesica::app::anatomy {

/// Closest point of triangle (a, b, c) to p (Ericson, Real-Time Collision Detection §5.1.5).
Eigen::Vector3d ClosestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c);

/// Unsigned distance (metres) from p to the nearest triangle of the mesh.
double DistanceToSurface(const physics::TriangleMesh& mesh, const Eigen::Vector3d& p);

/// Parameter t >= 0 of the first hit of origin + t * direction with the mesh, if any.
std::optional<double> FirstRayHit(const physics::TriangleMesh& mesh, const Eigen::Vector3d& origin,
                                  const Eigen::Vector3d& direction);

/// True when p is inside a closed surface (parity of crossings along a fixed, skewed ray).
bool IsInsideClosedSurface(const physics::TriangleMesh& mesh, const Eigen::Vector3d& p);

}  // namespace vesica::app::anatomy
