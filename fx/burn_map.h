#pragma once
// Per-triangle burn level of one surface (paper §2.5.3, after Bruyns and Montgomery): the
// touched element blackens at `rate_per_s` while the pedal is down, elements around it at the
// same rate scaled by 1 - d / radius (d: centroid distance to the touched element's centroid),
// cumulative over repeated contact and saturating at 1. Per triangle, not per vertex, because
// the paper burns elements and a triangle's level is exactly what the renderer's cell colour
// needs; neighbours are found by walking edge adjacency, so the spread follows the surface and
// does not jump across a gap to another fold.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "physics/mesh/triangle_mesh.h"

namespace vesica::fx {

struct BurnParams {
  double rate_per_s = 0.5;         ///< level gained per second of contact at the touched element, > 0
  double spread_radius_m = 0.004;  ///< fall-off radius, metres, > 0 (level gain 0 at this distance)
  double damage_threshold = 0.5;   ///< level in (0, 1] past which an element counts as damaged
  bool records_damage = true;      ///< liver and gallbladder wall: yes; membrane: no
};

/// An element first burnt strictly past the damage threshold.
struct DamageEvent {
  int element = -1;
  double time_s = 0;  ///< simulation time of the step in which it crossed
  double level = 0;   ///< its level at the end of that step
};

class BurnMap {
 public:
  /// `name` labels errors ("BurnMap 'liver': ..."). Throws for invalid params or a mesh with
  /// non-finite vertices or out-of-range indices.
  BurnMap(std::string name, const physics::TriangleMesh& surface, const BurnParams& params);

  /// Moves the centroids to the deformed positions (#V by 3, same vertex count); topology fixed.
  void UpdateGeometry(const physics::Vertices& vertices);

  /// One step of contact with `element` for dt_s seconds at simulation time time_s.
  void Burn(int element, double dt_s, double time_s);

  const std::string& name() const { return name_; }
  int num_elements() const { return static_cast<int>(level_.size()); }
  /// One float per triangle in [0, 1]: what the renderer reads.
  const std::vector<float>& levels() const { return level_float_; }
  double level(int element) const { return level_.at(static_cast<size_t>(element)); }
  const std::vector<DamageEvent>& damage_events() const { return damage_events_; }
  /// Sum of the rest areas (m^2) of the elements past the damage threshold.
  double damaged_area_m2() const { return damaged_area_m2_; }

 private:
  std::string name_;
  BurnParams params_;
  Eigen::MatrixX3i triangles_;
  std::vector<std::vector<int>> edge_neighbours_;  ///< per triangle, triangles across its edges
  Eigen::MatrixX3d centroids_;
  std::vector<double> rest_area_m2_;
  std::vector<double> level_;       ///< double accumulation keeps long sessions exact enough
  std::vector<float> level_float_;  ///< mirror of level_ for the renderer
  std::vector<char> damaged_;
  std::vector<DamageEvent> damage_events_;
  double damaged_area_m2_ = 0;
  // Scratch for the breadth-first spread, kept to avoid allocation per step.
  std::vector<int> visit_stamp_;
  int stamp_ = 0;
  std::vector<int> queue_;
};

}  // namespace vesica::fx
