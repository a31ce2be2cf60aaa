#pragma once
// Where the stylus' workspace sits over the patient. The trainee stands at the patient's right
// side, facing the patient (supine): the Omni's x (to the trainee's right) is the patient's
// cranial z, its y (up) the patient's anterior y, its z (toward the trainee) the patient's right
// (-x). Its workspace centre is above the tumour and positions are scaled, because an Omni's
// 160 x 120 x 70 mm box is smaller than the path from the skin to a liver tumour.

#include <Eigen/Core>

#include "device/stylus/stylus_state.h"
#include "physics/needle/needle_pose.h"

namespace vesica::app::biopsy {

struct StylusPlacement {
  Eigen::Matrix3d R_WB = Eigen::Matrix3d::Identity();  ///< the device base's axes in the world
  Eigen::Vector3d p_WBo_W = Eigen::Vector3d::Zero();   ///< the workspace centre in the world, m
  double scale = 1.0;                                  ///< world metres per device metre, > 0
};

/// The trainee at the patient's right side, the workspace centre `above_m` anterior of the
/// tumour's centre, positions scaled by `scale`.
StylusPlacement PlacementAtRightSide(const Eigen::Vector3d& tumour_centre_W, double above_m = 0.06, double scale = 1.5);

/// The needle in the world for a stylus sample (its direction unit).
physics::NeedlePose NeedleInWorld(const StylusPlacement& placement, const device::StylusState& stylus);

/// The stylus sample that puts the needle at `pose` (the inverse of NeedleInWorld; buttons 0).
device::StylusState StylusForNeedle(const StylusPlacement& placement, const physics::NeedlePose& pose);

/// Where the needle waits at the start: `above_m` anterior of the tumour's centre (outside a
/// supine patient's belly), pointing straight down (posterior), as a stylus sample.
device::StylusState StartingStylus(const StylusPlacement& placement, const Eigen::Vector3d& tumour_centre_W,
                                   double above_m = 0.11);

/// A world force as the device renders it (forces are not scaled).
Eigen::Vector3d ForceOnDevice(const StylusPlacement& placement, const Eigen::Vector3d& f_W);

}  // namespace vesica::app::biopsy
