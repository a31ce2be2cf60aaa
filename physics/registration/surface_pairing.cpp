#include "physics/registration/surface_pairing.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "physics/mesh/barycentric.h"

namespace vesica::physics {

RegistrationSurface::RegistrationSurface(const TetBoundary& boundary) {
  const Triangles& local = boundary.surface.triangles;
  triangles.resize(local.rows(), 3);
  for (Eigen::Index f = 0; f < local.rows(); ++f)
    for (int k = 0; k < 3; ++k) triangles(f, k) = boundary.surface_to_volume[local(f, k)];
}

SurfaceSnapshot::SurfaceSnapshot(const RegistrationSurface& s, const Vertices& x) : surface(&s), x_W(&x) {
  const Eigen::Index n = s.triangles.rows();
  centroid_W.resize(static_cast<size_t>(n));
  radius_m.resize(static_cast<size_t>(n));
  inward_normal_W.resize(static_cast<size_t>(n));
  for (Eigen::Index f = 0; f < n; ++f) {
    const Eigen::Vector3d a = x.row(s.triangles(f, 0)).transpose();
    const Eigen::Vector3d b = x.row(s.triangles(f, 1)).transpose();
    const Eigen::Vector3d c = x.row(s.triangles(f, 2)).transpose();
    const Eigen::Vector3d centroid = (a + b + c) / 3.0;
    centroid_W[static_cast<size_t>(f)] = centroid;
    radius_m[static_cast<size_t>(f)] =
        std::sqrt(std::max({(a - centroid).squaredNorm(), (b - centroid).squaredNorm(), (c - centroid).squaredNorm()}));
    const Eigen::Vector3d outward = (b - a).cross(c - a);
    const double twice_area = outward.norm();
    // A collapsed triangle has no normal to agree with: it is never paired.
    inward_normal_W[static_cast<size_t>(f)] =
        twice_area > 0.0 ? Eigen::Vector3d(-outward / twice_area) : Eigen::Vector3d::Zero();
  }
}

std::optional<SurfacePairing> PairControlPoint(const SurfaceSnapshot& snapshot, const ControlPoint& point,
                                               const PairingOptions& options) {
  const RegistrationSurface& surface = *snapshot.surface;
  const Vertices& x_W = *snapshot.x_W;
  std::optional<SurfacePairing> best;
  double best_distance = options.max_distance_m;
  const Eigen::Vector3d q = point.p_W;
  for (Eigen::Index f = 0; f < surface.triangles.rows(); ++f) {
    const size_t sf = static_cast<size_t>(f);
    // Bounding sphere about the centroid: no point of the triangle is nearer than |q - m| - r.
    const double reach = best_distance + snapshot.radius_m[sf];
    if ((q - snapshot.centroid_W[sf]).squaredNorm() > reach * reach) continue;
    const Eigen::Vector3d& inward = snapshot.inward_normal_W[sf];
    if (inward.isZero()) continue;
    if (options.check_normals && inward.dot(point.inward_normal_W) < options.min_normal_cosine) continue;
    const TrianglePoint closest = ClosestPointOnTriangle(q, x_W.row(surface.triangles(f, 0)).transpose(),
                                                         x_W.row(surface.triangles(f, 1)).transpose(),
                                                         x_W.row(surface.triangles(f, 2)).transpose());
    const double distance = (q - closest.point).norm();
    if (distance > best_distance) continue;
    best_distance = distance;
    SurfacePairing p;
    p.triangle = static_cast<int>(f);
    for (int k = 0; k < 3; ++k) p.nodes[static_cast<size_t>(k)] = surface.triangles(f, k);
    p.weights = closest.weights;
    p.p_Surface_W = closest.point;
    p.inward_normal_W = inward;
    p.distance_m = distance;
    best = p;
  }
  return best;
}

std::optional<SurfacePairing> PairControlPoint(const RegistrationSurface& surface, const Vertices& x_W,
                                               const ControlPoint& point, const PairingOptions& options) {
  return PairControlPoint(SurfaceSnapshot(surface, x_W), point, options);
}

}  // namespace vesica::physics
