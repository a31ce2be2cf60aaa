#pragma once
// Exact signed distance from a point to an axis-aligned ellipsoid's surface (D. Eberly,
// "Distance from a point to an ellipse, an ellipsoid, or a hyperellipsoid", 2013): the closest
// surface point x satisfies x_i = e_i^2 y_i / (t + e_i^2) for the one root t > -min e_i^2 of
// sum_i (e_i y_i / (t + e_i^2))^2 = 1 (y: the point relative to the centre, e: semi-axes).

#include <Eigen/Core>

namespace vesica::physics {

struct EllipsoidSurfacePoint {
  Eigen::Vector3d p_Surface_W;  ///< closest point on the surface, metres
  Eigen::Vector3d normal_W;     ///< unit outward normal of the surface there
  double signed_distance_m;     ///< |p - p_Surface|, negative inside the ellipsoid
};

/// Closest surface point of the ellipsoid centred at `centre_W` with semi-axes `semi_axes_m`
/// (along x, y, z, each > 0) to `p_W`. Deterministic bisection to double precision.
EllipsoidSurfacePoint ClosestPointOnEllipsoid(const Eigen::Vector3d& centre_W, const Eigen::Vector3d& semi_axes_m,
                                              const Eigen::Vector3d& p_W);

}  // namespace vesica::physics
