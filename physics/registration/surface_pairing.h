#pragma once
// Pairing of control points with the FE surface (seed sections 3.3-3.4, Fig. 2): each point binds
// to the nearest boundary triangle of the current mesh whose inward normal agrees with the point's
// normal; the barycentric weights of the closest point q_s on it are the rows of J.

#include <Eigen/Core>
#include <array>
#include <optional>
#include <vector>

#include "physics/mesh/mesh_topology.h"
#include "physics/mesh/mesh_types.h"
#include "physics/registration/control_point.h"

namespace vesica::physics {

/// The boundary of a tet mesh as the pairing sees it: triangles numbered by volume node.
struct RegistrationSurface {
  Triangles triangles;  ///< #F by 3 volume node indices, outward when read 0-1-2
  explicit RegistrationSurface(const TetBoundary& boundary);
};

/// Where a control point binds: q_s = sum_k weights[k] x(nodes[k]) on `triangle`.
struct SurfacePairing {
  int triangle = -1;
  std::array<int, 3> nodes{};
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();
  Eigen::Vector3d p_Surface_W = Eigen::Vector3d::Zero();      ///< q_s, metres
  Eigen::Vector3d inward_normal_W = Eigen::Vector3d::Zero();  ///< unit normal of the triangle, inward
  double distance_m = 0.0;                                    ///< |q_i - q_s|
};

struct PairingOptions {
  bool check_normals = true;
  double min_normal_cosine = 0.0;
  double max_distance_m = 0.05;
};

/// The surface's triangles at one configuration: bounding spheres and inward normals, computed
/// once a step and shared by every point paired in it.
struct SurfaceSnapshot {
  const RegistrationSurface* surface = nullptr;
  const Vertices* x_W = nullptr;
  std::vector<Eigen::Vector3d> centroid_W;
  std::vector<double> radius_m;
  std::vector<Eigen::Vector3d> inward_normal_W;  ///< zero for a collapsed triangle
  SurfaceSnapshot(const RegistrationSurface& surface, const Vertices& x_W);
};

/// Nearest eligible triangle for the point; nothing when none lies within max_distance_m (or none
/// faces the point's way). Triangles are culled by their bounding spheres, so the cost is one
/// squared distance per triangle plus a few closest-point tests.
std::optional<SurfacePairing> PairControlPoint(const SurfaceSnapshot& snapshot, const ControlPoint& point,
                                               const PairingOptions& options);
/// The same for one point at positions x_W (#V by 3), building the snapshot.
std::optional<SurfacePairing> PairControlPoint(const RegistrationSurface& surface, const Vertices& x_W,
                                               const ControlPoint& point, const PairingOptions& options);

}  // namespace vesica::physics
