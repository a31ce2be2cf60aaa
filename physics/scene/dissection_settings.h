#pragma once
// Settings of the coupled cholecystectomy scene (gallbladder paper §2.4-2.5, registration paper
// eqs. 1-4 and 6). SI units; every field names its unit and range.

#include <Eigen/Core>

#include "physics/grasp/grasp_state_machine.h"
#include "physics/scene/assistant_retraction.h"
#include "physics/tissue/spring_forces.h"

namespace vesica::physics {

enum class InstrumentRole { kGrasper, kCauteryHook };

/// Where an instrument enters: it pivots about the trocar's remote centre; yaw = pitch = 0
/// points the shaft along reference_direction_W (unit).
struct InstrumentMount {
  InstrumentRole role = InstrumentRole::kGrasper;
  Eigen::Vector3d p_RemoteCentre_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d reference_direction_W = Eigen::Vector3d::UnitZ();
};

struct DissectionSettings {
  double time_step_s = 0.005;  ///< physics step h, > 0 (200 Hz: docs/architecture.md's physics rate)
  /// Gravity on the gallbladder, m/s^2. Zero by default: the paper's scene has none, and in the
  /// patient the omentum and bowel carry the organs' weight.
  Eigen::Vector3d gravity_m_per_s2 = Eigen::Vector3d::Zero();
  SpringMaterial springs{20.0, 0.05};                ///< connective tissue, per spring (N/m, N s/m)
  AssistantRetractionSettings assistant_retraction;  ///< the fundus held by the assistant; off by default
  double attach_offset_m = 0.005;                    ///< paper §2.4: gallbladder offset toward the liver, > 0
  GraspSettings grasp;
  double grasp_compliance_m_per_N = 2e-3;  ///< W_soft of grasp rows (eq. 6): jaws and tissue give, >= 0
  /// The grasper holds its jaw's footprint (issue 37), a grasp_jaw_length_m x grasp_jaw_width_m
  /// rectangle centred on the touched point, long side along the shaft, as its mean
  /// (physics/fem/jaw_footprint.h), not the touched point alone (whose force follows the mesh);
  /// in series with the tissue's give under the jaw that the linear tets miss
  /// (physics/fem/jaw_subgrid_compliance.h: 28 % of the force on the trainer's gallbladder).
  /// That compliance is computed on a worker thread when the jaws close (0.1-0.3 s), adopted
  /// grasp_subgrid_adopt_steps later (a fixed step, so replays stay bit-identical; the step waits
  /// only if the worker is slower) and ramped in over grasp_subgrid_ramp_steps.
  bool grasp_holds_jaw_footprint = true;
  /// The closed jaws pressing the gallbladder press that footprint too (frictionless: its normal
  /// row), in series with the press's subgrid compliance, kept per surface vertex as computed
  /// (physics/scene/jaw_press_subgrid.h); open jaws and the hook press by the touched point.
  bool grasper_presses_jaw_footprint = true;
  double grasp_jaw_length_m = 0.010;            ///< > 0
  double grasp_jaw_width_m = 0.005;             ///< > 0
  double grasp_subgrid_patch_radius_m = 0.015;  ///< > 0; 0.015 is within 1 % of 0.025 (fidelity.md)
  int grasp_subgrid_adopt_steps = 60;           ///< >= 0 (0: computed within the grasping step)
  int grasp_subgrid_ramp_steps = 20;            ///< >= 1
  /// W_soft of contact rows, > 0: the instrument tip and the tissue's surface layer give a little
  /// (10 kN/m), which also keeps a contact on the liver's fixed region (no compliance) solvable.
  double contact_compliance_m_per_N = 1e-4;
  /// The most a contact may close of a penetration in one step, > 0 (m): a tool that starts or
  /// jumps deep into tissue pushes it out over several steps (at most this / h, 0.2 m/s by
  /// default) instead of flinging it out in one. Grasp rows are not clamped (the slip distance
  /// bounds them).
  double max_correction_per_step_m = 0.001;
  double contact_margin_m = 0.003;    ///< rays reach this far past the tip, so a touch is seen before penetration, > 0
  double touch_tolerance_m = 0.0005;  ///< a tool within this gap of a surface touches it (cautery), >= 0
  double grasp_reach_m = 0.003;       ///< closing jaws within this gap of the gallbladder take hold, >= 0
  double membrane_touch_radius_m = 0.003;  ///< hook tip radius that burns membrane elements, > 0
  double hook_length_m = 0.004;            ///< hook from the shaft tip, for the renderer and touch, > 0
  /// A tool pushing the liver loads it over its tip's footprint, a disc of this radius (m), as a
  /// rigid punch's traction (physics/bem/tool_contact_load.h; issue 37: the hit triangle's three
  /// vertices made the liver 40 % too stiff under a tool); 0: a point force on those vertices.
  double grasper_liver_footprint_radius_m = 0.004;  ///< closed jaws, about 5 x 10 mm, >= 0
  double hook_liver_footprint_radius_m = 0.0015;    ///< the hook's tip, about 3 mm across, >= 0
  int compliance_refresh_steps =
      20;  ///< refactor the constraint compliance at most this often after springs are cut, >= 1
  /// The refactorisation runs on a worker thread and is adopted this many steps after it began
  /// (a fixed step, so replays stay bit-identical; the step waits only if the worker is slower);
  /// 0: at once, in the step. >= 0, < compliance_refresh_steps.
  int compliance_adopt_steps = 15;

  // Contact of the gallbladder's surface nodes with what does not move in the simulation (issue
  // 30): the static obstacles (DissectionModel::obstacles) and the liver's current surface taken
  // as static for this contact (its Green's functions are not loaded by it: the gallbladder's
  // weight is tiny against the liver's stiffness). Each node nearer than obstacle_margin_m is a
  // one-sided row in the constraint solve, like an instrument's contact.
  bool gallbladder_rests_on_liver = true;  ///< the gallbladder's nodes may not enter the liver
  /// The contact acts only once the last spring is cut: until then the springs hold the
  /// gallbladder in its bed (where the anatomy's meshes may touch), and the committed recordings
  /// were made without it, so a dissection replays as before up to the moment it frees.
  bool static_contact_only_when_free = true;
  double obstacle_margin_m = 0.0005;  ///< a node this near a surface gets a contact row, > 0
  /// A node deeper than this inside an obstacle or the liver is left alone (pushing it out of a
  /// thin organ's far side would be wrong), > max_correction_per_step_m.
  double obstacle_max_depth_m = 0.005;
  /// W_soft of obstacle rows, > 0: the organs' surface gives 1 mm under 10 N.
  double obstacle_compliance_m_per_N = 1e-4;
  /// Coulomb friction coefficient of the gallbladder on organs and the liver, >= 0 (wet serosa on
  /// serosa; 0.4 holds it on slopes up to 22 degrees): two tangential rows per pressed node in the
  /// constraint solve; 0: no friction rows.
  double obstacle_friction = 0.4;
  /// Projected Gauss-Seidel sweeps of a step's constraint solve when it has obstacle rows, >= 1
  /// (without them the solver's default, 200).
  int obstacle_max_sweeps = 30;
  /// The obstacle solve also stops after a sweep that moved no row by more than this, m, > 0: it
  /// starts from the last step's forces, so a gallbladder at rest needs a few sweeps.
  double obstacle_tolerance_m = 1e-7;
};

}  // namespace vesica::physics
