#pragma once
// Issue 37's gallbladder study: the grasper's jaw (10 x 5 mm, as the reference places it) pulled
// (all components prescribed) or pressed (frictionless: the normal component only) by the
// reference's prescribed displacement, the bed (boundary nodes within 6 mm of a liver vertex)
// held, solved by linear statics with the trainer's linear tets (physics/fem), compared with the
// converged CalculiX reference (tool_load_reference.h).

#include <Eigen/Core>
#include <string>

#include "physics/fem/jaw_subgrid_compliance.h"
#include "physics/mesh/tetrahedral_mesh.h"
#include "physics/mesh/triangle_mesh.h"
#include "tools/convergence/tool_load_reference.h"

namespace vesica::convergence {

inline constexpr double kBedDistance_m = 0.006;  ///< reference.py's BED_DISTANCE_M
inline constexpr double kJawLength_m = 0.010;
inline constexpr double kJawWidth_m = 0.005;

/// How the jaw acts on the mesh.
enum class JawModel {
  /// The boundary nodes inside the rectangle are prescribed (the study's first model): the force
  /// follows how many nodes fall inside (1, 4, 4, 4, 10 on the committed gallbladders).
  kNodesInside,
  /// The jaw's footprint (physics/fem/jaw_footprint.h) moves on average with the jaw: one
  /// multiplier per prescribed component, a uniform traction over the exact rectangle.
  kFootprintMean,
  /// As kFootprintMean, and the footprint does not tilt either (its first moments along and across
  /// the jaw are held): a traction linear over the rectangle, three multipliers per component.
  kFootprintMeanAndTilt,
  /// The rectangle split into a fixed 4 x 2 grid of 2.5 x 2.5 mm cells, each cell's footprint
  /// moving on average with the jaw: a traction constant on each cell (24 multipliers for a pull),
  /// still independent of the mesh, and closer to the rigid jaw the reference prescribes (whose
  /// traction rises toward the rectangle's edges) than one uniform traction is.
  kFootprintCells,
  /// The trainer's grasp (physics/fem/jaw_subgrid_compliance.h): kFootprintMean in series with the
  /// subgrid compliance, the 10-node tets' 4 x 2-cell jaw less the linear tets' mean on the patch
  /// around the jaw. Linear tets only.
  kFootprintMeanWithSubgrid,
};

enum class JawLoad { kPull, kPress };

/// The element on the trainer's mesh (physics/fem/small_strain_stiffness.h).
enum class TetFormulation {
  kLinear,         ///< the trainer's 4-node tet
  kNodalPressure,  ///< 4-node, average nodal pressure (Bonet & Burton 1998)
  kQuadratic,      ///< 10-node, the mesh's edges split at their midpoints
};

const char* JawModelName(JawModel model);
const char* TetFormulationName(TetFormulation formulation);

struct GallbladderGraspResult {
  int nodes = 0;                                      ///< the mesh's vertices (corners)
  int dof_nodes = 0;                                  ///< the solve's nodes (with the quadratic tets' midpoints)
  int jaw_nodes = 0;                                  ///< nodes prescribed or reached by the footprint
  double mean_edge_m = 0;                             ///< mean boundary edge
  Eigen::Vector3d force_N = Eigen::Vector3d::Zero();  ///< total reaction on the jaw
  double force_error = 0;                             ///< |F - F_ref| / |F_ref|
};

/// Whether a point lies in the jaw's footprint (reference.py's in_jaw).
bool InJaw(const Eigen::Vector3d& p_m, const ToolLoadReference& ref, JawLoad load = JawLoad::kPull);

GallbladderGraspResult SolveGallbladderGrasp(const physics::TetrahedralMesh& gallbladder,
                                             const physics::TriangleMesh& liver, const ToolLoadReference& ref,
                                             JawModel model = JawModel::kFootprintMean, JawLoad load = JawLoad::kPull,
                                             TetFormulation formulation = TetFormulation::kLinear,
                                             const physics::JawSubgridSettings& subgrid = {});

/// data/anatomy/gallbladder_<nodes>.vtu and tests/fem/data/gallbladder_{grasp,press}_reference.txt.
physics::TetrahedralMesh ReadTrainerGallbladder(const std::string& source_dir, int nodes);
ToolLoadReference ReadGallbladderGraspReference(const std::string& source_dir);
ToolLoadReference ReadGallbladderPressReference(const std::string& source_dir);

}  // namespace vesica::convergence
