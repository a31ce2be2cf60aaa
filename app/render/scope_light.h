#pragma once
// Where the laparoscope's light leaves the scope, relative to the lens (no VTK). A scope's light
// fibres end beside the lens, on the side of its light post; set a little off the line of sight,
// the light makes each instrument cast a shadow that meets the instrument's tip when the tip
// touches tissue: the depth cue surgeons judge contact by. The offset is far larger than a 10 mm
// scope's fibre ring (about 4 mm): with the light that close to the lens, the shadow hides
// behind the instrument that casts it (its parallax is offset x height / distance, under a
// millimetre at 8 mm above tissue 15 cm away). 23 mm to the left of and above the lens puts the
// shadow of a shaft held a few centimetres over the tissue beside it on the screen, as a second
// light would. Sideways matters: a shaft entering from the top is lengthened, not uncovered, by
// a shadow that falls straight down; this one falls down and to the right of the hook's shaft
// (entering from the upper right), along the grasper's (entering from the upper left).

#include <Eigen/Core>

namespace vesica::app {

/// The light's offset from the lens along the image's right and up axes (m).
inline constexpr double kScopeLightRight_m = -0.019;
inline constexpr double kScopeLightUp_m = 0.013;

/// The light's position (patient frame) for a lens at eye_W with the image's unit axes.
inline Eigen::Vector3d ScopeLightPosition(const Eigen::Vector3d& eye_W, const Eigen::Vector3d& right_W,
                                          const Eigen::Vector3d& up_W) {
  return eye_W + kScopeLightRight_m * right_W + kScopeLightUp_m * up_W;
}

}  // namespace vesica::app
