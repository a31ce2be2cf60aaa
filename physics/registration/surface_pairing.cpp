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

std::optional<SurfacePairing> PairControlPoint(const RegistrationSurface& surface, const Vertices& x_W,
                                               const ControlPoint& point, const PairingOptions& options) {
  std::optional<SurfacePairing> best;
  double best_distance = options.max_distance_m;
  const Eigen::Vector3d q = point.p_W;
  for (Eigen::Index f = 0; f < surface.triangles.rows(); ++f) {
    const Eigen::Vector3d a = x_W.row(surface.triangles(f, 0)).transpose();
    const Eigen::Vector3d b = x_W.row(surface.triangles(f, 1)).transpose();
    const Eigen::Vector3d c = x_W.row(surface.triangles(f, 2)).transpose();
    // Bounding sphere about the centroid: no point of the triangle is nearer than |q - m| - r.
    const Eigen::Vector3d centroid = (a + b + c) / 3.0;
    const double radius =
        std::sqrt(std::max({(a - centroid).squaredNorm(), (b - centroid).squaredNorm(), (c - centroid).squaredNorm()}));
    if ((q - centroid).norm() - radius > best_distance) continue;
    const Eigen::Vector3d outward = (b - a).cross(c - a);
    const double twice_area = outward.norm();
    if (!(twice_area > 0.0)) continue;  // a collapsed triangle has no normal to agree with
    const Eigen::Vector3d inward = -outward / twice_area;
    if (options.check_normals && inward.dot(point.inward_normal_W) < options.min_normal_cosine) continue;
    const TrianglePoint closest = ClosestPointOnTriangle(q, a, b, c);
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

}  // namespace vesica::physics
