#pragma once
// Calot's (hepatocystic) triangle of a scenario ([calot_triangle] and its [[calot_triangle.tubes]]):
// the cystic duct, the cystic artery and the common ducts as centrelines from the patient's side,
// how their ends are held, and where the plan divides the cystic structures, so that anatomical
// variants are data. The physics side is physics/calot/triangle_description.h; ToPhysics below.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "physics/calot/triangle_description.h"

namespace vesica::app {

struct CalotTubeConfig {
  std::string name;
  physics::calot::TubeKind kind = physics::calot::TubeKind::kCysticDuct;
  std::vector<Eigen::Vector3d> points_m;  ///< >= 2, the patient's side (held) first
  physics::calot::TubeEndHold end = physics::calot::TubeEndHold::kNeck;
  double planned_cut_s = 0.6;            ///< where the plan divides it, 0 < s < 1 from the patient's side
  std::optional<double> outer_radius_m;  ///< the kind's literature value when absent
  std::string source;                    ///< "file.toml:42", for errors
};

struct CalotTriangleConfig {
  std::string variant;                                 ///< what the debrief and History call this anatomy
  Eigen::Vector3d neck_m = Eigen::Vector3d::Zero();  ///< the gallbladder's neck, where the cystic structures end
  double node_spacing_m = 0.0025;
  std::vector<CalotTubeConfig> tubes;
};

/// The physics' description: each kind's material (physics::calot::DefaultTubeMaterial) with the
/// radius given; the cystic duct and the common ducts carry bile from both ends, the artery blood
/// from its patient's side only.
physics::calot::TriangleDescription ToPhysics(const CalotTriangleConfig& config);

/// "cystic_duct", "cystic_artery", "common_hepatic_duct", "common_bile_duct".
const char* TubeKindKey(physics::calot::TubeKind kind);

}  // namespace vesica::app
