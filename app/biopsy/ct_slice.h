#pragma once
// The guidance image a radiologist uses during a CT-guided biopsy: the CT resliced through the
// needle as the patient breathes, in two planes (issue 34): the axial slice through the needle's
// tip, and the oblique plane that contains the needle. No Qt: the pixels and the geometry to draw
// on them; app/needle_mode shows them.
//
// Axial images follow the radiological convention: seen from the feet, the patient's right on
// the image's left (columns run to the patient's left, +x), anterior at the top (rows run
// posterior, -y).

#include <Eigen/Core>
#include <vector>

#include "physics/needle/deformed_ct.h"
#include "physics/needle/needle_pose.h"

namespace vesica::app::biopsy {

struct SlicePlane {
  Eigen::Vector3d centre_W = Eigen::Vector3d::Zero();   ///< the image's centre, world
  Eigen::Vector3d column_W = Eigen::Vector3d::UnitX();  ///< unit: where columns increase
  Eigen::Vector3d row_W = -Eigen::Vector3d::UnitY();    ///< unit, orthogonal to column_W: where rows increase
  double pixel_m = 0.0015;                              ///< > 0: pixel size
  int columns = 160, rows = 160;                        ///< > 0
};

/// The axial plane through p_W (z = p_W.z), centred on p_W.
SlicePlane AxialSliceThrough(const Eigen::Vector3d& p_W, double pixel_m = 0.0015, int size = 160);

/// The plane that contains the needle: columns along the needle's direction D (the tip right of
/// centre), rows along the axis perpendicular to D nearest to posterior (-y) or, for a needle that
/// points along y, to caudal (-z). Centred on the tip.
SlicePlane ObliqueSliceAlong(const physics::NeedlePose& pose, double pixel_m = 0.0015, int size = 160);

/// Where a world point falls on the plane, in pixels (column, row; pixel (0, 0)'s centre is at
/// (0.5, 0.5)), and its distance off the plane.
struct SlicePoint {
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
  double off_plane_m = 0.0;
};
SlicePoint ProjectOntoSlice(const SlicePlane& plane, const Eigen::Vector3d& p_W);

/// The world point at the centre of pixel (column, row).
Eigen::Vector3d PixelCentre(const SlicePlane& plane, int column, int row);

/// Hounsfield units of every pixel (row-major, rows x columns), sampled through the breathing
/// deformation `ct` holds.
std::vector<float> SampleSlice(const physics::DeformedCt& ct, const SlicePlane& plane);

/// A grey level 0-255 for an HU value through a window (level, width): the abdominal window is
/// level 40, width 400.
unsigned char WindowHu(float hu, double level = 40.0, double width = 400.0);

}  // namespace vesica::app::biopsy
