#pragma once
// What the view draws of Calot's triangle in one frame (issue 36): the tubes as the physics has
// them (whole or cut into pieces), the clips on them, the fat cells still intact, and the open
// ends that bleed or leak bile. Plain data, patient frame; empty when the scenario has no triangle.

#include <Eigen/Core>
#include <vector>

#include "physics/calot/tube_kind.h"

namespace vesica::app {

struct CalotTubeDrawing {
  physics::calot::TubeKind kind = physics::calot::TubeKind::kCysticDuct;
  std::vector<Eigen::Vector3d> centreline_W;  ///< >= 2 points, the piece's nodes
  double radius_m = 0.0015;
};

struct CalotClipDrawing {
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();       ///< on the tube's centreline
  Eigen::Vector3d along_W = Eigen::Vector3d::UnitX();  ///< the tube's tangent there
  double tube_radius_m = 0.0015;                       ///< the clip spans the tube
};

struct CalotLeakDrawing {
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();
  bool blood = false;  ///< else bile
};

struct CalotDrawing {
  std::vector<CalotTubeDrawing> tubes;
  std::vector<CalotClipDrawing> clips;
  std::vector<Eigen::Vector3d> fat_cells_W;  ///< intact cells' centres
  /// The same cells' rest places (the layer's lattice), same order; empty: at rest (fat_cells_W).
  std::vector<Eigen::Vector3d> fat_cells_rest_W;
  double fat_cell_size_m = 0.002;
  std::vector<CalotLeakDrawing> leaks;
  bool empty() const { return tubes.empty() && fat_cells_W.empty(); }
};

}  // namespace vesica::app
