#include "app/anatomy/retracted_liver_shape.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vesica::app::anatomy {

namespace {

// Polynomial smooth maximum (the intersection of two fields) over a width k.
double SmoothMax(double a, double b, double k) {
  const double h = std::clamp(0.5 - 0.5 * (b - a) / k, 0.0, 1.0);
  return b + (a - b) * h + k * h * (1 - h);
}

double Radians(double deg) { return deg * std::numbers::pi / 180.0; }

double Square(double x) { return x * x; }

// How far the edge and the hilum bow toward the hilum, and the visceral surface recedes, at s:
// 1 at 10 cm either side of the fundus.
double Bend(double s_m) { return Square(s_m / 0.1); }

// The round ligament's notch: how far the edge is cut back toward the hilum at s.
double FissureNotch(const RetractedLiverShape& l, double s_m) {
  return l.fissure_notch_m * std::exp(-Square((s_m - l.fissure_s_m) / l.fissure_width_m));
}

// Height of the visceral surface above the frame's plane at (s, u): convex (receding toward the
// lobes' ends), the quadrate lobe bulging, the umbilical fissure's groove. u is measured from
// the bowed edge line.
double VisceralHeight(const RetractedLiverShape& l, double s_m, double u_m) {
  const double quadrate = l.quadrate_bulge_m * std::exp(-Square((s_m - 0.040) / 0.016) - Square((u_m - 0.045) / 0.03));
  const double fissure = l.fissure_depth_m * std::exp(-Square((s_m - l.fissure_s_m) / (0.7 * l.fissure_width_m)));
  return -l.convexity_m * Bend(s_m) + quadrate - fissure;
}

// Signed distance (negative inside) to the outline in the visceral surface's plane: a rectangle
// from the edge (u = 0) past the hilum, from the right lobe's end to the left's, whose corners
// are rounded with the lobes' end radii. u is measured from the notched, bowed edge line.
double OutlineDistance(const RetractedLiverShape& l, double s_m, double u_m) {
  const double top_m = l.hilum_depth_m + 0.08;  // past the hilum, where the hilum's cap cuts it
  const double centre_s = 0.5 * (l.left_extent_m - l.right_extent_m);
  const double half_s = 0.5 * (l.left_extent_m + l.right_extent_m);
  const double radius = s_m < centre_s ? l.right_end_radius_m : l.left_end_radius_m;
  const Eigen::Vector2d p(std::abs(s_m - centre_s), std::abs(u_m - 0.5 * top_m));
  const Eigen::Vector2d q = p - Eigen::Vector2d(half_s, 0.5 * top_m) + Eigen::Vector2d::Constant(radius);
  return q.cwiseMax(0.0).norm() + std::min(std::max(q.x(), q.y()), 0.0) - radius;
}

// How far the outline's rounded lobe ends lift the edge away from the straight line at s.
double EndLift(const RetractedLiverShape& l, double s_m) {
  const double right_corner = -l.right_extent_m + l.right_end_radius_m;
  const double left_corner = l.left_extent_m - l.left_end_radius_m;
  if (s_m < right_corner) {
    const double x = std::min(right_corner - s_m, l.right_end_radius_m);
    return l.right_end_radius_m - std::sqrt(Square(l.right_end_radius_m) - Square(x));
  }
  if (s_m > left_corner) {
    const double x = std::min(s_m - left_corner, l.left_end_radius_m);
    return l.left_end_radius_m - std::sqrt(Square(l.left_end_radius_m) - Square(x));
  }
  return 0.0;
}

}  // namespace

Eigen::Vector3d LiverSurfaceFrame::Out() const { return visceral_normal.normalized(); }

Eigen::Vector3d LiverSurfaceFrame::Along() const {
  const Eigen::Vector3d n = Out();
  return (edge_direction - edge_direction.dot(n) * n).normalized();
}

Eigen::Vector3d LiverSurfaceFrame::Across() const { return Out().cross(Along()); }

Eigen::Vector3d LiverSurfaceFrame::At(double s_m, double u_m, double q_m) const {
  return edge_point_m + s_m * Along() + u_m * Across() + q_m * Out();
}

namespace {

// Where p lies relative to the liver's surface frame and outline.
struct LiverCoordinates {
  double s;       ///< along the edge
  double u;       ///< across, from the bowed edge line
  double depth;   ///< below the visceral surface (positive inside)
  double inward;  ///< in-plane distance inside the notched outline (negative outside)
  double alpha;   ///< the wedge's angle at s, radians
};

LiverCoordinates Locate(const RetractedLiverShape& l, const Eigen::Vector3d& p_W) {
  LiverCoordinates c;
  const Eigen::Vector3d r = p_W - l.frame.edge_point_m;
  c.s = r.dot(l.frame.Along());
  c.u = r.dot(l.frame.Across()) - l.bow_m * Bend(c.s);
  c.depth = VisceralHeight(l, c.s, c.u) - r.dot(l.frame.Out());
  c.inward = -OutlineDistance(l, c.s, c.u - FissureNotch(l, c.s));
  const double t = std::clamp(c.s / l.left_wedge_from_m, 0.0, 1.0);
  c.alpha = Radians(l.right_wedge_deg + (l.left_wedge_deg - l.right_wedge_deg) * t);
  return c;
}

}  // namespace

double RetractedLiverField(const RetractedLiverShape& l, const GallbladderCentreline& gallbladder,
                           const Eigen::Vector3d& p_W) {
  const LiverCoordinates c = Locate(l, p_W);
  // The liver thickens from its border inward: a thin crest all round the outline, the wedge
  // opening faster in the right lobe than in the left.
  const double visceral = -c.depth;
  const double diaphragmatic = (c.depth - l.edge_thickness_m - c.inward * std::tan(c.alpha)) * std::cos(c.alpha);
  // The hilum's side curves toward the edge at the lobes' ends (no square corners).
  const double end = (c.s - 0.5 * (l.left_extent_m - l.right_extent_m)) / (0.5 * (l.left_extent_m + l.right_extent_m));
  const double hilum = c.u - l.hilum_depth_m + l.hilum_end_lift_m * Square(Square(end));
  double wedge = SmoothMax(visceral, diaphragmatic, l.edge_rounding_m);
  wedge = SmoothMax(wedge, hilum, l.hilum_rounding_m);
  // Carve the fossa: inside only where inside the wedge and clear of the gallbladder.
  const double fossa = l.gallbladder_gap_m - GallbladderDistance(gallbladder, p_W);
  return SmoothMax(fossa, wedge, l.fossa_blend_m);
}

double RetractedLiverCrestDistance(const RetractedLiverShape& l, const Eigen::Vector3d& p_W) {
  const LiverCoordinates c = Locate(l, p_W);
  return std::hypot(c.inward, c.depth);
}

Eigen::Vector3d RetractedLiverEdgePoint(const RetractedLiverShape& l, double s_m) {
  const double u = FissureNotch(l, s_m) + EndLift(l, s_m);
  return l.frame.At(s_m, l.bow_m * Bend(s_m) + u, VisceralHeight(l, s_m, u));
}

Box RetractedLiverBounds(const RetractedLiverShape& l) {
  // The corners of the wedge's bounding prism in the surface frame, thickest at the hilum.
  const double widest = std::max(l.right_extent_m, l.left_extent_m);
  const double thick = 0.08 * std::tan(Radians(std::max(l.right_wedge_deg, l.left_wedge_deg))) + l.edge_thickness_m;
  const double bend = Bend(widest + 0.01);
  Box box{Eigen::Vector3d::Constant(1e9), Eigen::Vector3d::Constant(-1e9)};
  for (double s : {-l.right_extent_m - 0.01, l.left_extent_m + 0.01})
    for (double u : {-0.01, l.hilum_depth_m + l.bow_m * bend + 0.01})
      for (double q : {l.quadrate_bulge_m + 0.01, -thick - l.convexity_m * bend - 0.01}) {
        const Eigen::Vector3d p = l.frame.At(s, u, q);
        box.min_m = box.min_m.cwiseMin(p);
        box.max_m = box.max_m.cwiseMax(p);
      }
  return box;
}

}  // namespace vesica::app::anatomy
