#pragma once
// The liver as a wedge in the right upper quadrant: a rounded slab, thick at the right lobe
// (negative x) and thin at the left lobe, domed above and flatter on its inferior (visceral)
// surface, with a fossa carved where the gallbladder lies so that the two never touch.

#include <Eigen/Core>

#include "app/anatomy/gallbladder_shape.h"
#include "app/anatomy/implicit_surface.h"

namespace vesica::app::anatomy {

struct LiverShape {
  Eigen::Vector3d centre_m{-0.06, 0.0, 0.05};  ///< middle of the slab; metres
  double half_width_m = 0.10;                  ///< along x (right-left); about 20 cm across
  double half_depth_m = 0.075;                 ///< along y (posterior-anterior); about 15 cm
  double right_lobe_up_m = 0.07;               ///< dome height above the centre at the right edge
  double right_lobe_down_m = 0.035;            ///< depth below the centre at the right edge
  double left_lobe_up_m = 0.022;               ///< the same at the thin left edge
  double left_lobe_down_m = 0.012;
  double squareness = 3.0;           ///< superellipse exponent of the outline (2 = ellipse)
  double gallbladder_gap_m = 0.004;  ///< clearance between the fossa and the gallbladder
  double fossa_blend_m = 0.003;      ///< rounding of the fossa's rim
};

/// Field of the liver (negative inside; about metres near the surface), with the gallbladder
/// fossa carved out: every point within gallbladder_gap_m of the gallbladder is outside.
double LiverField(const LiverShape& liver, const GallbladderCentreline& gallbladder, const Eigen::Vector3d& p_W);

/// A box that contains the liver.
Box LiverBounds(const LiverShape& liver);

}  // namespace vesica::app::anatomy
