#pragma once
// What vesica-register writes (docs/registration.md):
//   registered_NNNN.vtu   the mesh at each frame, point data "displacement_m" (3 components)
//   registered.pvd        ParaView's index of the series, one DataSet per frame at its time
//   displacement.csv      frame,time_s,node,ux_m,uy_m,uz_m (every node of every frame)
//   residuals.csv         frame,time_s,points,paired,mean_gap_m,max_gap_m,constraint_iterations,fem_iterations

#include <filesystem>
#include <vector>

#include "physics/mesh/tetrahedral_mesh.h"
#include "physics/registration/registration_solver.h"

namespace vesica::app::registration {

/// One registered frame: the mesh's positions after its last step and that step's report.
struct RegisteredFrame {
  int frame = 0;
  double time_s = 0.0;
  int points = 0;
  physics::Vertices positions_W;
  physics::RegistrationStepReport last_step;
};

/// Writes the files above into `dir` (which must exist). Throws std::runtime_error naming the file.
void WriteRegistrationOutputs(const std::filesystem::path& dir, const physics::TetrahedralMesh& rest,
                              const std::vector<RegisteredFrame>& frames);

}  // namespace vesica::app::registration
