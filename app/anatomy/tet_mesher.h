#pragma once
// Quality tetrahedral meshes of a closed surface with TetGen 1.5 (Si, ACM TOMS 2015).

#include <string>

#include "physics/mesh/mesh_quality.h"
#include "physics/mesh/tetrahedral_mesh.h"
#include "physics/mesh/triangle_mesh.h"

namespace vesica::app::anatomy {

/// Runs TetGen on a closed, outward surface with the given command-line switches (e.g.
/// "pq1.4/15a1e-7YQ"). Tets come back positively oriented. Throws std::runtime_error when TetGen
/// fails, naming the switches.
physics::TetrahedralMesh Tetrahedralise(const physics::TriangleMesh& surface, const std::string& switches);

struct TetQualityRequest {
  double max_radius_edge = 1.4;  ///< TetGen -q bound on circumradius / shortest edge (> 1)
  double min_dihedral_deg = 15;  ///< TetGen -q/ bound on the smallest dihedral angle, degrees
  bool keep_surface = true;      ///< TetGen -Y: no Steiner points on the boundary
  int optimisation_level = 2;    ///< TetGen -O level 0..10 (flips, smoothing, insert/delete)
};

struct SizedTetMesh {
  physics::TetrahedralMesh mesh;
  std::string switches;  ///< the TetGen switches that produced it, for the record
};

/// Quality mesh whose node count is as close to `target_nodes` as a TetGen maximum-volume bound
/// can bring it (bisection on the bound, deterministic).
SizedTetMesh TetrahedraliseToNodeCount(const physics::TriangleMesh& surface, int target_nodes,
                                       const TetQualityRequest& quality);

}  // namespace vesica::app::anatomy
