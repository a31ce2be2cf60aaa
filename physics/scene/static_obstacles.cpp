#include "physics/scene/static_obstacles.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "physics/collision/ellipsoid_distance.h"

namespace vesica::physics {

void CheckStaticObstacles(const StaticObstacles& obstacles) {
  for (const ObstacleTube& t : obstacles.tubes) {
    const std::string what = "static obstacle tube '" + t.name + "': ";
    if (t.centreline_W.size() < 2) throw std::invalid_argument(what + "needs at least 2 centreline points");
    if (!(t.radius_m > 0.0) || !std::isfinite(t.radius_m))
      throw std::invalid_argument(what + "radius " + std::to_string(t.radius_m) + " m must be finite and > 0");
    for (size_t k = 0; k < t.centreline_W.size(); ++k) {
      if (!t.centreline_W[k].allFinite())
        throw std::invalid_argument(what + "point " + std::to_string(k) + " is not finite");
      if (k > 0 && (t.centreline_W[k] - t.centreline_W[k - 1]).norm() == 0.0)
        throw std::invalid_argument(what + "points " + std::to_string(k - 1) + " and " + std::to_string(k) +
                                    " coincide");
    }
  }
  for (const ObstacleEllipsoid& e : obstacles.ellipsoids) {
    const std::string what = "static obstacle ellipsoid '" + e.name + "': ";
    if (!e.centre_W.allFinite()) throw std::invalid_argument(what + "centre is not finite");
    if (!e.semi_axes_m.allFinite() || !(e.semi_axes_m.minCoeff() > 0.0))
      throw std::invalid_argument(what + "semi-axes must be finite and > 0");
  }
}

ObstacleProximity TubeProximity(const ObstacleTube& tube, const Eigen::Vector3d& p_W) {
  // The union of capsules: the nearest centreline point overall decides (ties: the first segment).
  double best = 1e300;
  Eigen::Vector3d nearest = tube.centreline_W.front();
  for (size_t k = 0; k + 1 < tube.centreline_W.size(); ++k) {
    const Eigen::Vector3d& a = tube.centreline_W[k];
    const Eigen::Vector3d ab = tube.centreline_W[k + 1] - a;
    const double s = std::clamp((p_W - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    const Eigen::Vector3d c = a + s * ab;
    const double d = (p_W - c).squaredNorm();
    if (d < best) {
      best = d;
      nearest = c;
    }
  }
  ObstacleProximity out;
  const Eigen::Vector3d r = p_W - nearest;
  const double distance = r.norm();
  if (distance > 0.0) {
    out.normal_W = r / distance;
  } else {
    // On the centreline itself: any direction across it; take one perpendicular to the first segment.
    const Eigen::Vector3d axis = (tube.centreline_W[1] - tube.centreline_W[0]).normalized();
    out.normal_W = axis.unitOrthogonal();
  }
  out.p_Surface_W = nearest + tube.radius_m * out.normal_W;
  out.signed_distance_m = distance - tube.radius_m;
  return out;
}

std::optional<ObstacleProximity> NearestObstacle(const StaticObstacles& obstacles, const Eigen::Vector3d& p_W,
                                                 double within_m, double max_depth_m) {
  std::optional<ObstacleProximity> best;
  auto consider = [&](const ObstacleProximity& c) {
    if (c.signed_distance_m > within_m || c.signed_distance_m <= -max_depth_m) return;
    if (!best || c.signed_distance_m < best->signed_distance_m) best = c;
  };
  for (const ObstacleEllipsoid& e : obstacles.ellipsoids) {
    // Cheap rejection first: outside the box grown by within_m the point cannot be within reach.
    if (((p_W - e.centre_W).cwiseAbs() - e.semi_axes_m).maxCoeff() > within_m) continue;
    const EllipsoidSurfacePoint s = ClosestPointOnEllipsoid(e.centre_W, e.semi_axes_m, p_W);
    consider({s.p_Surface_W, s.normal_W, s.signed_distance_m});
  }
  for (const ObstacleTube& t : obstacles.tubes) consider(TubeProximity(t, p_W));
  return best;
}

}  // namespace vesica::physics
