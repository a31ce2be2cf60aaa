#pragma once
// The liver as the surgeon sees it once the assistant has pushed the gallbladder's fundus over
// the liver's edge: the right lobe turned up so that its visceral surface faces the umbilical
// laparoscope. Its outline is rounded (the lobes' ends curve into the edge); its border is a thin,
// sharp edge from which the liver thickens toward the hilum and the bare area (a wedge, thicker in
// the right lobe than the left); the visceral surface carries the gallbladder's shallow fossa
// (carved from the gallbladder's own shape), segment IV's quadrate lobe bulging between the fossa
// and the umbilical fissure, and that fissure with the round ligament's notch in the edge.
// Built in a frame on the visceral surface (LiverSurfaceFrame).

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
  double right_extent_m = 0.14;     ///< the right lobe's reach along the edge (s < 0)
  double left_extent_m = 0.17;      ///< the left lobe's reach (s > 0)
  double hilum_depth_m = 0.10;      ///< from the edge across the visceral surface to the hilum
  double right_wedge_deg = 58;      ///< angle between visceral and diaphragmatic surfaces, right lobe
  double left_wedge_deg = 34;       ///< the same at the left lobe (thinner)
  double left_wedge_from_m = 0.08;  ///< s at which the wedge reaches the left lobe's angle
  double edge_thickness_m = 0.002;  ///< thickness at the border's crest: a sharp edge
  double edge_rounding_m = 0.002;   ///< blend of the crest
  double hilum_rounding_m = 0.03;   ///< blend where the visceral surface turns at the hilum
  double hilum_end_lift_m = 0.045;  ///< the hilum's side comes this much nearer the edge at the lobes' ends
  /// Radius (in the visceral surface's plane) with which each lobe's end curves into the edge:
  /// the outline has no corners.
  double right_end_radius_m = 0.09;
  double left_end_radius_m = 0.08;
  /// The edge and the hilum bow toward the hilum by this at 10 cm either side of the fundus
  /// (the edge's outline curves; the lobes' ends lie lower in the picture).
  double bow_m = 0.018;
  /// The visceral surface is convex: it recedes from the camera by this at 10 cm either side.
  double convexity_m = 0.012;
  /// The umbilical fissure (the round ligament's groove between segment IV and the left lobe):
  /// where it crosses the edge (s), the notch it cuts into the edge, its groove's width and depth.
  double fissure_s_m = 0.065;
  double fissure_notch_m = 0.012;
  double fissure_width_m = 0.009;
  double fissure_depth_m = 0.006;
  /// Segment IV's quadrate lobe: a bulge of the visceral surface between the fossa and the fissure.
  double quadrate_bulge_m = 0.005;
  double gallbladder_gap_m = 0.004;  ///< clearance between the fossa and the gallbladder
  double fossa_blend_m = 0.006;      ///< rounding of the fossa's rim
};

/// Field of the retracted liver (negative inside; about metres near the surface), fossa carved.
double RetractedLiverField(const RetractedLiverShape& liver, const GallbladderCentreline& gallbladder,
                           const Eigen::Vector3d& p_W);

/// About how far p is from the crest of the liver's border (the thin edge all round the outline),
/// metres: where the mesh must be finest.
double RetractedLiverCrestDistance(const RetractedLiverShape& liver, const Eigen::Vector3d& p_W);

/// The crest of the inferior edge at s (metres along the edge from the frame's origin): where
/// the visceral surface, bowed, notched and convex as the field makes it, meets the diaphragmatic
/// one (the middle of the outline; toward the lobes' ends the outline curves away from it).
Eigen::Vector3d RetractedLiverEdgePoint(const RetractedLiverShape& liver, double s_m);

/// A box that contains the liver.
Box RetractedLiverBounds(const RetractedLiverShape& liver);

}  // namespace vesica::app::anatomy
