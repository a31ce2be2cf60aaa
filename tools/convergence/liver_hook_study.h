#pragma once
// Issue 37's liver study: the hook's tip (a gallbladder-bed vertex and its one-ring, the footprint,
// pushed in by the reference's prescribed displacement) on a liver surface, solved by the BEM
// (capacitance solver) after `levels` passes of graded refinement toward the tip, compared with
// the converged CalculiX reference (tool_load_reference.h).

#include <Eigen/Core>
#include <string>

#include "physics/bem/bem_model.h"
#include "physics/bem/tool_footprint.h"
#include "physics/mesh/triangle_mesh.h"
#include "tools/convergence/tool_load_reference.h"

namespace vesica::convergence {

struct LiverHookResult {
  int vertices = 0;
  double contact_edge_m = 0;                          ///< mean edge of the footprint's triangles: h at the tool
  Eigen::Vector3d force_N = Eigen::Vector3d::Zero();  ///< total contact force
  /// The contact traction integrated over the footprint's triangles only (its hat functions cut
  /// at the footprint's edge) instead of over each contact node's whole lumped area.
  Eigen::Vector3d footprint_force_N = Eigen::Vector3d::Zero();
  double footprint_force_error = 0;
  double force_error = 0;         ///< |F - F_ref| / |F_ref|
  double displacement_error = 0;  ///< relative L2 over the trainer's free vertices off the footprint
  double precompute_s = 0;        ///< wall clock of PrecomputeBemModel (uncached)
};

/// Where the study's liver is refined: toward the hook's tip (radii 4, 2.4, 1.44 ... footprints;
/// the footprint's radius is the tip's longest ring edge), or, as a trainer could precompute it
/// once for any contact there, toward the whole gallbladder bed (vertices labelled bed, radii
/// 0.5, 0.3 ... footprints).
enum class LiverGrading { kTowardTip, kTowardBed };

/// The liver of the study's refinement level: the trainer's surface after `levels` passes.
struct LiverHookSetup {
  physics::TriangleMesh surface;
  std::vector<int> contact;              ///< every vertex on the footprint's (refined) triangles
  std::vector<int> footprint_triangles;  ///< the (refined) triangles the tool covers
  std::vector<int> footprint_parents;    ///< the trainer's ring triangle each of them lies in
  int tip = -1;                          ///< the hook's tip vertex (same index on every level)
  double footprint_radius_m = 0;         ///< the tip's longest ring edge
  double contact_edge_m = 0;
};
LiverHookSetup MakeLiverHookSetup(const physics::TriangleMesh& trainer_liver, const ToolLoadReference& ref, int levels,
                                  LiverGrading grading = LiverGrading::kTowardTip);

/// Precomputes the BEM on the setup's surface (no cache) and solves the indentation.
LiverHookResult SolveLiverHook(const physics::TriangleMesh& trainer_liver, const ToolLoadReference& ref,
                               const LiverHookSetup& setup);
/// The same on a model already precomputed for the setup's surface (precompute_s left 0).
LiverHookResult SolveLiverHook(const physics::TriangleMesh& trainer_liver, const ToolLoadReference& ref,
                               const LiverHookSetup& setup, const physics::BemModel& model);

/// Issue 37's fix: the same load as a traction over the tool's footprint (the tip's one-ring;
/// rho = 1 - the tip's barycentric coordinate in its ring triangle, so rho = 1 on the ring's outer
/// edges) carried by traction modes (physics/bem/tool_footprint.h, default: uniform and punch, 6
/// unknowns) instead of prescribed nodes. The displacement error skips the reference's contact
/// vertices as SolveLiverHook does.
physics::ToolFootprint OneRingFootprint(const physics::TriangleMesh& trainer_liver, const LiverHookSetup& setup);
LiverHookResult SolveLiverHookWithModes(const physics::TriangleMesh& trainer_liver, const ToolLoadReference& ref,
                                        const LiverHookSetup& setup, const physics::BemModel& model,
                                        const physics::FootprintOptions& options = {});

/// The trainer's own tool footprint (physics/bem/tool_contact_load.h, as the scene loads the liver):
/// a disc of `radius_m` around the tip vertex, in the plane normal to the one-ring's mean normal,
/// pushed by the reference's displacement along its normal only (the scene's contact row): the
/// magnitude of the force along that normal (N). No CalculiX reference exists for it; the study
/// compares levels.
double LiverDiscPushForce(const physics::TriangleMesh& trainer_liver, const ToolLoadReference& ref,
                          const LiverHookSetup& setup, const physics::BemModel& model, double radius_m);

/// data/anatomy/liver.vtk and tests/bem/data/liver_hook_reference.txt under the source tree.
physics::TriangleMesh ReadTrainerLiver(const std::string& source_dir);
ToolLoadReference ReadLiverHookReference(const std::string& source_dir);

}  // namespace vesica::convergence
