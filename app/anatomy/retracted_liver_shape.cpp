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

double RetractedLiverField(const RetractedLiverShape& l, const GallbladderCentreline& gallbladder,
                           const Eigen::Vector3d& p_W) {
  const Eigen::Vector3d r = p_W - l.frame.edge_point_m;
  const double s = r.dot(l.frame.Along());
  const double depth = -r.dot(l.frame.Out()) - l.convexity_m * (s / 0.1) * (s / 0.1);
  const double u = r.dot(l.frame.Across()) - l.bow_m * (s / 0.1) * (s / 0.1);
  // The wedge opens from the edge: thick right lobe, thin left lobe.
  const double t = std::clamp(s / l.left_wedge_from_m, 0.0, 1.0);
  const double alpha = Radians(l.right_wedge_deg + (l.left_wedge_deg - l.right_wedge_deg) * t);
  const double visceral = -depth;
  const double diaphragmatic = depth * std::cos(alpha) - (u + l.edge_thickness_m / std::tan(alpha)) * std::sin(alpha);
  const double hilum = u - l.hilum_depth_m;
  const double lobes = std::max(s - l.left_extent_m, -l.right_extent_m - s);
  double wedge = SmoothMax(visceral, diaphragmatic, l.edge_rounding_m);
  wedge = SmoothMax(wedge, hilum, l.hilum_rounding_m);
  wedge = SmoothMax(wedge, lobes, l.side_rounding_m);
  // Carve the fossa: inside only where inside the wedge and clear of the gallbladder.
  const double fossa = l.gallbladder_gap_m - GallbladderDistance(gallbladder, p_W);
  return SmoothMax(fossa, wedge, l.fossa_blend_m);
}

Eigen::Vector3d RetractedLiverEdgePoint(const RetractedLiverShape& l, double s_m) {
  const double bend = (s_m / 0.1) * (s_m / 0.1);
  return l.frame.At(s_m, l.bow_m * bend, -l.convexity_m * bend);
}

Box RetractedLiverBounds(const RetractedLiverShape& l) {
  // The corners of the wedge's bounding prism in the surface frame, thickest at the hilum.
  const double thick = (l.hilum_depth_m + 0.02) * std::tan(Radians(std::max(l.right_wedge_deg, l.left_wedge_deg)));
  Box box{Eigen::Vector3d::Constant(1e9), Eigen::Vector3d::Constant(-1e9)};
  for (double s : {-l.right_extent_m - 0.01, l.left_extent_m + 0.01})
    for (double u : {-0.02, l.hilum_depth_m + l.bow_m * 7 + 0.01})
      for (double q : {0.01, -thick - l.convexity_m * 7}) {
        const Eigen::Vector3d p = l.frame.At(s, u, q);
        box.min_m = box.min_m.cwiseMin(p);
        box.max_m = box.max_m.cwiseMax(p);
      }
  return box;
}

}  // namespace vesica::app::anatomy
