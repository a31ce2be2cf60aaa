#pragma once
// Where an instrument may be drawn (issue 30): never through tissue. The physics moves the
// tissue out of the way of the tool's working point, but the commanded tip can still lie inside
// an organ it is not in contact with (the hook burning the membrane from behind the
// gallbladder: 4.3 mm inside in the committed dissection). The view then draws the tool stopped
// where its shaft first meets a surface; the status strip says how far the hand went past it.

#include <array>

#include "physics/collision/surface_ray_caster.h"
#include "physics/instrument/instrument_pose.h"
#include "physics/scene/dissection_model.h"

namespace vesica::app {

class DrawnToolLimit {
 public:
  /// Casts against the model's liver and gallbladder boundary surfaces.
  explicit DrawnToolLimit(const physics::DissectionModel& model);

  /// The insertion each instrument is drawn at for `poses` on the current (deformed) surfaces:
  /// the commanded insertion, or less where the shaft from its remote centre crosses a surface
  /// before the commanded tip. liver and gallbladder: #V x 3 current positions (boundary
  /// numbering for the gallbladder).
  std::array<double, 2> Update(const std::array<physics::InstrumentPose, 2>& poses, const physics::Vertices& liver,
                               const physics::Vertices& gallbladder);

 private:
  const physics::DissectionModel& model_;
  physics::SurfaceRayCaster caster_;
  int liver_id_ = -1, gallbladder_id_ = -1;
};

}  // namespace vesica::app
