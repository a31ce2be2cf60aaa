#pragma once
// Barycentric location of points in triangles and tetrahedra (used to attach springs, grasp
// points and contacts to deforming elements).

#include <Eigen/Core>

#include "physics/mesh/tetrahedral_mesh.h"

namespace vesica::physics {

/// Barycentric weights (wa, wb, wc), summing to 1, of p's projection onto the plane of (a, b, c).
Eigen::Vector3d TriangleBarycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                    const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// Closest point of triangle (a, b, c) to p, with its barycentric weights (all in [0, 1]).
struct TrianglePoint {
  Eigen::Vector3d point;
  Eigen::Vector3d weights;
};
TrianglePoint ClosestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                     const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// Barycentric weights (w0..w3), summing to 1, of p in tet (x0..x3); all >= 0 iff p is inside.
Eigen::Vector4d TetBarycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& x0,
                               const Eigen::Vector3d& x1, const Eigen::Vector3d& x2,
                               const Eigen::Vector3d& x3);

/// A point bound to a tet of a mesh: x = sum_k weights[k] * vertices(tets(tet, k)).
struct TetLocation {
  int tet = -1;
  Eigen::Vector4d weights = Eigen::Vector4d::Zero();
};

/// The tet containing p; if p is outside the mesh, the tet whose most negative weight is the
/// least negative (weights then extrapolate, which is what a point just outside needs).
TetLocation LocateInTetMesh(const TetrahedralMesh& mesh, const Eigen::Vector3d& p);

/// Position of a located point in the mesh's current configuration.
Eigen::Vector3d Interpolate(const TetrahedralMesh& mesh, const TetLocation& location);

}  // namespace vesica::physics
