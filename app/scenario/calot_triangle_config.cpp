#include "app/scenario/calot_triangle_config.h"

#include <algorithm>

namespace vesica::app {

physics::calot::TriangleDescription ToPhysics(const CalotTriangleConfig& config) {
  using physics::calot::TubeKind;
  physics::calot::TriangleDescription d;
  d.p_Neck_W_m = config.neck_m;
  for (const CalotTubeConfig& c : config.tubes) {
    physics::calot::TubeDescription t;
    t.name = c.name;
    t.kind = c.kind;
    t.centreline_m = c.points_m;
    t.material = physics::calot::DefaultTubeMaterial(c.kind);
    if (c.outer_radius_m) {
      t.material.outer_radius_m = *c.outer_radius_m;
      t.material.wall_thickness_m = std::min(t.material.wall_thickness_m, *c.outer_radius_m);
    }
    t.node_spacing_m = config.node_spacing_m;
    t.end_hold = c.end;
    t.start_pressurised = true;                              // bile from the liver, blood from the hepatic artery
    t.end_pressurised = c.kind != TubeKind::kCysticArtery;  // the gallbladder's bile; no back-bleeding modelled
    t.source = c.source;
    d.tubes.push_back(std::move(t));
  }
  return d;
}

const char* TubeKindKey(physics::calot::TubeKind kind) {
  switch (kind) {
    case physics::calot::TubeKind::kCysticDuct:
      return "cystic_duct";
    case physics::calot::TubeKind::kCysticArtery:
      return "cystic_artery";
    case physics::calot::TubeKind::kCommonHepaticDuct:
      return "common_hepatic_duct";
    case physics::calot::TubeKind::kCommonBileDuct:
      return "common_bile_duct";
  }
  return "cystic_duct";
}

}  // namespace vesica::app
