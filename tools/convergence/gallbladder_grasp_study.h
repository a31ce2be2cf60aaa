#pragma once
// Issue 37's gallbladder study: the grasper's jaw (10 x 5 mm, as the reference places it) pulled
// by the reference's prescribed displacement, the bed (boundary nodes within 6 mm of a liver
// vertex) held, solved by linear statics with the trainer's linear tets (physics/fem), compared
// with the converged CalculiX reference (tool_load_reference.h).

#include <Eigen/Core>
#include <string>

#include "physics/mesh/tetrahedral_mesh.h"
#include "physics/mesh/triangle_mesh.h"
#include "tools/convergence/tool_load_reference.h"

namespace vesica::convergence {

inline constexpr double kBedDistance_m = 0.006;  ///< reference.py's BED_DISTANCE_M
inline constexpr double kJawLength_m = 0.010;
inline constexpr double kJawWidth_m = 0.005;

struct GallbladderGraspResult {
  int nodes = 0;
  int jaw_nodes = 0;                                  ///< boundary nodes in the jaw's footprint (prescribed)
  double mean_edge_m = 0;                             ///< mean boundary edge
  Eigen::Vector3d force_N = Eigen::Vector3d::Zero();  ///< total reaction on the jaw's nodes
  double force_error = 0;                             ///< |F - F_ref| / |F_ref|
};

/// Whether a point lies in the jaw's footprint (reference.py's in_jaw).
bool InJaw(const Eigen::Vector3d& p_m, const ToolLoadReference& ref);

GallbladderGraspResult SolveGallbladderGrasp(const physics::TetrahedralMesh& gallbladder,
                                             const physics::TriangleMesh& liver, const ToolLoadReference& ref);

/// data/anatomy/gallbladder_<nodes>.vtu and tests/fem/data/gallbladder_grasp_reference.txt.
physics::TetrahedralMesh ReadTrainerGallbladder(const std::string& source_dir, int nodes);
ToolLoadReference ReadGallbladderGraspReference(const std::string& source_dir);

}  // namespace vesica::convergence
