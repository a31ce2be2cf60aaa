#pragma once
// The committed recorded biopsy (data/recordings/biopsy.csv): a stylus stream, written by
// vesica-script-biopsy, of a radiologist's textbook biopsy on the synthetic patient. The needle
// comes in anteriorly between the 7th and 8th costal cartilages, straight down onto the tumour,
// at 15 mm/s; the sample is taken 7 mm short of the tumour's centre (a good specimen) at end
// expiration (t = 8 s at 0.25 Hz, when the tumour is where the CT shows it); then it withdraws.

#include "app/biopsy/stylus_placement.h"
#include "device/stylus/stylus_recording.h"

namespace vesica::app::biopsy {

struct ScriptedBiopsyPlan {
  Eigen::Vector3d entry_above_skin_W{-0.075, 0.13, -0.045};  ///< the needle's tip before it enters, world
  Eigen::Vector3d direction_W{0.0, -1.0, 0.0};               ///< straight down (posterior)
  Eigen::Vector3d target_W{-0.075, 0.027, -0.045};           ///< where the sample is taken
  double hold_before_s = 1.0;                                ///< still above the skin
  double insert_until_s = 8.0;                               ///< reaches the target then, and samples
  double button_down_s = 0.3;                                ///< the biopsy button held this long
  double withdraw_from_s = 8.5;
  double withdraw_until_s = 12.0;
  double sample_period_s = 0.01;  ///< one recorded sample every 10 ms
};

/// The stylus stream for the plan, through `placement` (PlacementAtRightSide of the patient's
/// tumour for the committed file).
device::StylusRecording ScriptBiopsy(const StylusPlacement& placement, const ScriptedBiopsyPlan& plan = {});

}  // namespace vesica::app::biopsy
