#pragma once
// The liver as the surgeon sees it once the assistant has pushed the gallbladder's fundus over
// the liver's edge: the right lobe turned up so that its visceral surface faces the umbilical
// laparoscope, a wedge whose thin end is the sharp inferior edge, thick toward the hilum and the
// bare area, the left lobe thinner than the right, with the gallbladder fossa carved from the
// gallbladder's own shape. Built in a frame on the visceral surface (LiverSurfaceFrame).

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "app/anatomy/gallbladder_shape.h"
#include "app/anatomy/implicit_surface.h"

namespace vesica::app::anatomy {

/// A frame on the liver's visceral surface: origin on the inferior edge, s along the edge toward
/// the left lobe, u across the visceral surface from the edge toward the hilum, q out of the
/// surface into the abdomen. Patient frame, metres.
struct LiverSurfaceFrame {
  Eigen::Vector3d edge_point_m{-0.045, 0.05, 0.06};
  Eigen::Vector3d visceral_normal{0.2, 0.25, -1.0};  ///< out of the visceral surface; normalised on use
  Eigen::Vector3d edge_direction{1.0, 0.0, 0.0};     ///< toward the left lobe; made orthogonal to the normal

  Eigen::Vector3d Along() const;   ///< unit s axis
  Eigen::Vector3d Across() const;  ///< unit u axis (edge -> hilum)
  Eigen::Vector3d Out() const;     ///< unit q axis (the visceral surface's outward normal)
  /// The patient-frame point at (s, u, q).
  Eigen::Vector3d At(double s_m, double u_m, double q_m) const;
};

struct RetractedLiverShape {
  LiverSurfaceFrame frame;
  double right_extent_m = 0.13;     ///< the right lobe's reach along the edge (s < 0)
  double left_extent_m = 0.17;      ///< the left lobe's reach (s > 0)
  double hilum_depth_m = 0.095;     ///< from the edge across the visceral surface to the hilum
  double right_wedge_deg = 46;      ///< angle between visceral and diaphragmatic surfaces, right lobe
  double left_wedge_deg = 30;       ///< the same at the left lobe (thinner)
  double left_wedge_from_m = 0.08;  ///< s at which the wedge reaches the left lobe's angle
  double edge_thickness_m = 0.012;  ///< thickness at the inferior edge (sharp, not a blade)
  double edge_rounding_m = 0.010;   ///< blend of the edge
  double hilum_rounding_m = 0.03;   ///< blend where the visceral surface turns at the hilum
  double side_rounding_m = 0.07;    ///< blend of the lobes' ends
  /// The edge and the hilum bow toward the hilum by this at 10 cm either side of the fundus
  /// (the edge's outline curves; the lobes' ends lie lower in the picture).
  double bow_m = 0.012;
  /// The visceral surface is convex: it recedes from the camera by this at 10 cm either side.
  double convexity_m = 0.01;
  double gallbladder_gap_m = 0.004;  ///< clearance between the fossa and the gallbladder
  double fossa_blend_m = 0.006;      ///< rounding of the fossa's rim
};

/// Field of the retracted liver (negative inside; about metres near the surface), fossa carved.
double RetractedLiverField(const RetractedLiverShape& liver, const GallbladderCentreline& gallbladder,
                           const Eigen::Vector3d& p_W);

/// The crest of the inferior edge at s (metres along the edge from the frame's origin): where
/// the visceral surface, bowed and convex as the field makes it, meets the diaphragmatic one.
Eigen::Vector3d RetractedLiverEdgePoint(const RetractedLiverShape& liver, double s_m);

/// A box that contains the liver.
Box RetractedLiverBounds(const RetractedLiverShape& liver);

}  // namespace vesica::app::anatomy
