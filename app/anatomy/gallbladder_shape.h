#pragma once
// The gallbladder as a chain of rounded cones along its centreline: fundus, body, neck
// (Hartmann's pouch) and a cystic-duct stub, in the patient frame (x left, y anterior, z cranial).

#include <Eigen/Core>
#include <vector>

#include "app/anatomy/implicit_surface.h"

namespace vesica::app::anatomy {

struct GallbladderCentreline {
  std::vector<Eigen::Vector3d> points_m;  ///< fundus first, cystic-duct end last; metres
  std::vector<double> radii_m;            ///< lumen-plus-wall radius at each point; metres
  double blend_m = 0;                     ///< smooth-union width at the joints; metres
};

/// An adult gallbladder about 8 cm from fundus to the end of the duct stub, about 3 cm across at
/// the body, lying under the inferior surface of the liver's right lobe with the fundus anterior.
GallbladderCentreline DefaultGallbladderCentreline();

/// Approximate signed distance (metres) from p_W to the gallbladder surface, negative inside.
double GallbladderDistance(const GallbladderCentreline& centreline, const Eigen::Vector3d& p_W);

/// Box around the gallbladder grown by `margin_m` on every side.
Box GallbladderBounds(const GallbladderCentreline& centreline, double margin_m);

}  // namespace vesica::app::anatomy
