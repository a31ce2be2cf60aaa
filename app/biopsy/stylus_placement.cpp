#include "app/biopsy/stylus_placement.h"

namespace vesica::app::biopsy {

StylusPlacement PlacementAtRightSide(const Eigen::Vector3d& tumour_centre_W, double above_m, double scale) {
  StylusPlacement placement;
  // Columns: the device's x, y, z in the world (right-handed: x cross y = z).
  placement.R_WB.col(0) = Eigen::Vector3d::UnitZ();   // trainee's right: cranial
  placement.R_WB.col(1) = Eigen::Vector3d::UnitY();   // up: anterior
  placement.R_WB.col(2) = -Eigen::Vector3d::UnitX();  // toward the trainee: the patient's right
  placement.p_WBo_W = tumour_centre_W + Eigen::Vector3d(0.0, above_m, 0.0);
  placement.scale = scale;
  return placement;
}

physics::NeedlePose NeedleInWorld(const StylusPlacement& placement, const device::StylusState& stylus) {
  physics::NeedlePose pose;
  pose.tip_m = placement.p_WBo_W + placement.scale * (placement.R_WB * stylus.p_BTip_B);
  pose.direction = (placement.R_WB * stylus.d_B).normalized();
  return pose;
}

device::StylusState StylusForNeedle(const StylusPlacement& placement, const physics::NeedlePose& pose) {
  device::StylusState stylus;
  stylus.p_BTip_B = placement.R_WB.transpose() * (pose.tip_m - placement.p_WBo_W) / placement.scale;
  stylus.d_B = (placement.R_WB.transpose() * pose.direction).normalized();
  return stylus;
}

device::StylusState StartingStylus(const StylusPlacement& placement, const Eigen::Vector3d& tumour_centre_W,
                                   double above_m) {
  physics::NeedlePose pose;
  pose.tip_m = tumour_centre_W + Eigen::Vector3d(0.0, above_m, 0.0);
  pose.direction = -Eigen::Vector3d::UnitY();
  return StylusForNeedle(placement, pose);
}

Eigen::Vector3d ForceOnDevice(const StylusPlacement& placement, const Eigen::Vector3d& f_W) {
  return placement.R_WB.transpose() * f_W;
}

}  // namespace vesica::app::biopsy
