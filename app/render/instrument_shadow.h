#pragma once
// Instrument shadows on the organs (internal to app/render): each instrument is a few capsules
// (shaft, jaws, hook) and every organ fragment whose ray to the scope's light passes through one
// is darkened, in the fragment shader. Exact per pixel at the cost of a few dot products per
// fragment and capsule, with a soft edge that widens with the distance from the instrument (the
// light's fibre ring is not a point). No shadow map, no extra render pass.

#include <Eigen/Core>
#include <vector>

class vtkActor;
class vtkCamera;

namespace vesica::app {

/// One part of an instrument that casts a shadow: a capsule in the display frame (display_frame.h).
struct ShadowCaster {
  Eigen::Vector3d a_D, b_D;  ///< ends of its axis (m)
  double radius_m = 0;
};

/// At most this many capsules cast shadows (more are ignored).
inline constexpr int kMaxShadowCasters = 8;
/// How much light a shadow's core takes away (0..1): the cavity's walls scatter the rest back.
inline constexpr double kShadowStrength = 0.65;

/// Makes `organ` receive instrument shadows (adds the shader code; no casters yet).
void ReceiveInstrumentShadows(vtkActor* organ);

/// Sets the casters and the light (display frame) on a receiving actor, converted to the
/// camera's view coordinates the shader works in. `enabled` false: no shadow.
void SetInstrumentShadows(vtkActor* organ, const std::vector<ShadowCaster>& casters, const Eigen::Vector3d& light_D,
                          vtkCamera* camera, bool enabled);

}  // namespace vesica::app
