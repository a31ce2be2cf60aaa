#pragma once
// One instrument in VTK (internal to app/render): a black insulated shaft through its trocar and
// its working end: two fenestrated steel jaws opening with the jaw angle (grasper), or an L-hook
// electrode, insulated up to its bare metal tip (cautery). The right hand's port may hold, by
// exchange, a clip applier (slotted jaws with a titanium clip loaded between them while open) or
// scissors (two slender blades). The jaws turn amber-red while a grasp slips; the hook glows while
// the cautery cuts.

#include <vtkSmartPointer.h>

#include <Eigen/Core>
#include <vector>

#include "app/render/grasper_jaw.h"
#include "app/render/instrument_shadow.h"
#include "app/render/render_frame.h"
#include "app/scenario/scenario.h"

class vtkActor;
class vtkLineSource;
class vtkSphereSource;

namespace vesica::app {

/// The grasper's jaw for a shaft of radius r (m): as wide as the shaft, 18 mm long.
GrasperJawShape GrasperJawFor(double shaft_radius_m);

/// The working end's lengths (m): the hook's stem from the shaft's end to the bend, its bare
/// metal part (the rest of the stem is insulated), and its foot.
inline constexpr double kHookStem_m = 0.012;
inline constexpr double kHookBareStem_m = 0.004;
inline constexpr double kHookFoot_m = 0.006;
/// The clip applier's and the scissors' jaws, hinge to tip (m).
inline constexpr double kClipApplierJaw_m = 0.014;
inline constexpr double kScissorBlade_m = 0.016;

class InstrumentActors {
 public:
  /// `reference_direction`: the shaft direction at yaw = pitch = 0 (unit). `pbr`: physically
  /// based materials (metallic steel, black plastic) instead of Phong.
  InstrumentActors(const InstrumentConfig& config, const Eigen::Vector3d& remote_centre,
                   const Eigen::Vector3d& reference_direction, bool pbr = false);
  const std::vector<vtkSmartPointer<vtkActor>>& actors() const { return actors_; }
  const Eigen::Vector3d& remote_centre() const { return remote_centre_; }
  const Eigen::Vector3d& reference_direction() const { return reference_direction_; }

  void Update(const InstrumentFrame& frame);

  /// The parts that cast shadows, as drawn by the last Update (display frame).
  const std::vector<ShadowCaster>& shadow_casters() const { return casters_; }

 private:
  void Steel(vtkActor* actor) const;
  void Insulation(vtkActor* actor) const;
  void BuildExchangeTools();
  /// Two jaws hinged at `hinge` opening by the jaw angle in the plane of d and side.
  void PlaceJaws(vtkActor* a, vtkActor* b, const Eigen::Vector3d& hinge, const Eigen::Vector3d& d,
                 const Eigen::Vector3d& side, double jaw_angle_rad, double length_m, double width_m);

  InstrumentConfig config_;
  Eigen::Vector3d remote_centre_;
  Eigen::Vector3d reference_direction_;
  bool pbr_;
  GrasperJawShape jaw_shape_;
  vtkSmartPointer<vtkLineSource> shaft_line_, sleeve_line_, stem_line_, foot_line_;
  vtkSmartPointer<vtkSphereSource> glow_;
  vtkSmartPointer<vtkActor> shaft_, jaw_a_, jaw_b_, sleeve_, stem_, foot_, glow_actor_;
  // The right hand's exchange: clip applier jaws and its loaded clip, scissor blades.
  vtkSmartPointer<vtkActor> applier_a_, applier_b_, loaded_clip_, blade_a_, blade_b_;
  std::vector<vtkSmartPointer<vtkActor>> actors_;
  std::vector<ShadowCaster> casters_;
};

}  // namespace vesica::app
