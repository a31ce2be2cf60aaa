#pragma once
// What the cautery hook does during one physics step: the input of every fx effect.

#include <Eigen/Core>
#include <string>
#include <vector>

namespace vesica::fx {

/// The surface the hook tip touches.
enum class CauterySurface { kNone, kLiver, kGallbladder, kMembrane };

const char* ToString(CauterySurface surface);

struct CauteryContact {
  CauterySurface surface = CauterySurface::kNone;  ///< kNone: the hook touches nothing
  int element = -1;                                ///< touched triangle of that surface (ignored when surface is kNone)
  /// Barycentric weights of the touch point in `element` (each in [0, 1], summing to 1).
  Eigen::Vector3d barycentric = Eigen::Vector3d::Constant(1.0 / 3.0);
  Eigen::Vector3d p_WTip_W = Eigen::Vector3d::Zero();  ///< hook tip in world, metres
  bool pedal_down = false;                             ///< the cautery pedal (current flows only while it is down)
  double dt_s = 0;                                     ///< length of the step, seconds, >= 0
  /// kMembrane: further membrane elements under the hook tip besides `element` (the hook's
  /// radius spans several thin elements); each burns and fades like `element`.
  std::vector<int> more_membrane_elements;

  /// Burning happens only while the pedal is down and the hook touches a surface.
  bool active() const { return pedal_down && surface != CauterySurface::kNone; }
};

/// Throws std::invalid_argument for negative/non-finite dt, non-finite tip, or barycentric
/// weights outside [0, 1] or not summing to 1 (1e-6). The element index is checked by the
/// surface's owner, which knows its size.
void ValidateCauteryContact(const CauteryContact& contact);

}  // namespace vesica::fx
