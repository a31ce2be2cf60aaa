#pragma once
// Calot's triangle in a dissection session (issue 36): the tubes and their fat layer stepped after
// the scene, the gallbladder's neck moving them, the right hand's instrument acting on them (the
// hook burns fat, the clip applier clips and the scissors cut when their jaws close across a
// tube, every tip pushes the tubes, the grasper's tips part the fat) and the training logic fed a
// snapshot of it each step (docs/calot-training.md's integration note).

#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

#include "app/calot/calot_metrics.h"
#include "app/calot/calot_snapshot.h"
#include "app/scenario/calot_triangle_config.h"
#include "device/input/input_frame.h"
#include "physics/calot/fat_layer.h"
#include "physics/calot/triangle_structures.h"
#include "physics/collision/surface_ray_caster.h"
#include "physics/scene/dissection_scene.h"

namespace vesica::app {

/// Where the laparoscope looks from (ScopePoseOf), for what of the tubes it sees.
struct CalotCamera {
  Eigen::Vector3d p_Eye_W_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d forward_W = Eigen::Vector3d::UnitX();                    ///< unit line of sight
  Eigen::Vector3d up_W = Eigen::Vector3d::UnitZ();                         ///< unit image up, orthogonal to forward_W
  double vertical_view_angle_rad = 70.0 * 3.14159265358979323846 / 180.0;  ///< (0, pi)
  double aspect = 16.0 / 9.0;                                              ///< image width over height, > 0
};

/// A scenario's triangle and the camera, what a session needs to run the Calot step.
struct CalotSessionSetup {
  CalotTriangleConfig triangle;
  CalotCamera camera;
};

/// Instrument geometry the step uses (m, rad).
struct CalotToolGeometry {
  double jaw_length_m = 0.018;       ///< a 5 mm instrument's jaws, hinge to tip (app/render/grasper_jaw.h)
  double jaw_capture_gap_m = 0.004;  ///< a tube whose wall is within this of the jaws' segment is between them
  double jaw_open_rad = 0.1;         ///< above this the jaws count as open (B toggles 0 / open)
  double tip_radius_m = 0.0025;      ///< a 5 mm instrument's tip, pushing tubes and fat
  /// The L-hook's wire, pushing tubes: thinner than the shaft, so that its burn (hook_burn_radius_m)
  /// reaches the fat against a tube's wall, as a surgeon peels the sleeve off a duct with it.
  double hook_wire_radius_m = 0.001;
  double hook_burn_radius_m = 0.002;  ///< fat cells within this of the hook's tip share its energy
  double hook_power_W = 30.0;         ///< coagulation power of the hook's pedal
  double neck_radius_m = 0.008;       ///< gallbladder nodes within this of the neck at rest move it
  /// What the camera sees of the tubes (rays past the liver and the gallbladder) is refreshed
  /// every this many steps (20 Hz at 200 Hz physics), >= 1.
  int visibility_period_steps = 10;
  double occlusion_margin_m = 0.001;  ///< a surface this near the tube's point does not hide it
};

class CalotTriangleStep {
 public:
  /// Throws std::invalid_argument (naming the tube) for a bad triangle, or when no gallbladder
  /// node lies within neck_radius_m of the neck.
  CalotTriangleStep(const CalotSessionSetup& setup, const physics::DissectionScene& scene,
                    const CalotToolGeometry& geometry = {});

  /// One step after the scene's: the neck from the gallbladder, the tubes, the tools, the fat,
  /// then the snapshot into the metrics. `pedal_burns`: the hook's pedal is down and the hook in
  /// the port. After the case ended (bile duct injury) the model still moves but nothing is judged.
  void Step(const physics::DissectionScene& scene, const device::InputFrame& input, bool pedal_burns);

  const physics::calot::TriangleStructures& tubes() const { return tubes_; }
  const physics::calot::FatLayer& fat() const { return *fat_; }
  const app::calot::CalotMetrics& metrics() const { return metrics_; }
  const app::calot::CalotSnapshot& last_snapshot() const { return snapshot_; }
  bool case_ended() const { return metrics_.CaseEnded(); }
  /// The fraction of the tube's centreline the camera sees, fat aside (at the last refresh).
  double seen_fraction(int tube) const { return seen_fraction_.at(static_cast<std::size_t>(tube)); }
  /// The gallbladder FEM nodes that carry the neck (within neck_radius_m of it at rest).
  const std::vector<int>& neck_nodes() const { return neck_nodes_; }
  /// Where the neck is now (the mean of its gallbladder nodes' displacement added to the rest).
  const Eigen::Vector3d& neck_W_m() const { return p_Neck_W_m_; }
  /// The jaws' segment of the right hand's instrument: from jaw_length_m back along the shaft to its tip.
  std::array<Eigen::Vector3d, 2> RightJawSegment(const physics::DissectionScene& scene,
                                                 const physics::InstrumentPose& pose) const;
  /// The grasper's two jaw tips, apart by the jaw angle across the shaft (together when closed).
  std::array<Eigen::Vector3d, 2> GrasperJawTips(const physics::DissectionScene& scene,
                                                const physics::InstrumentPose& pose) const;

 private:
  void ActWithRightTool(const physics::DissectionScene& scene, const device::InputFrame& input, bool pedal_burns);
  void FillSnapshot(const physics::DissectionScene& scene);
  /// Fraction of the tube's centreline samples in the camera's frustum and not behind the
  /// liver or the gallbladder (refreshed every visibility_period_steps).
  double SeenFraction(const physics::DissectionScene& scene, int tube);
  double LowerThirdSeparatedFraction(const physics::DissectionScene& scene) const;

  CalotSessionSetup setup_;
  CalotToolGeometry geometry_;
  double h_s_ = 0;
  physics::calot::TriangleStructures tubes_;
  std::unique_ptr<physics::calot::FatLayer> fat_;
  std::vector<int> neck_nodes_;  // gallbladder FEM nodes near the neck at rest
  Eigen::Vector3d neck_rest_mean_m_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d p_Neck_W_m_ = Eigen::Vector3d::Zero();
  std::vector<int> lower_third_springs_;  // connective tissue springs whose gallbladder end is near the neck
  physics::SurfaceRayCaster organs_;
  int liver_surface_ = -1, gallbladder_surface_ = -1;
  std::vector<double> seen_fraction_;  // per tube, at the last refresh
  long steps_ = 0;
  bool right_jaw_was_open_ = false;
  bool assessment_stopped_ = false;
  std::vector<app::calot::CalotEvent> pending_events_;
  app::calot::CalotSnapshot snapshot_;
  app::calot::CalotMetrics metrics_;
};

}  // namespace vesica::app
