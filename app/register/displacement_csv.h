#pragma once
// Reading back vesica-register's displacement.csv (frame,time_s,node,ux_m,uy_m,uz_m) as a
// physics::DisplacementSeries on the registered mesh: what a scenario hands to
// BreathingPatient::DriveLiver (through MakePointMotion) to replay a measured breathing motion.

#include <filesystem>

#include "physics/mesh/tetrahedral_mesh.h"
#include "physics/registration/displacement_series.h"

namespace vesica::app::registration {

/// `rest`: the mesh vesica-register was given. Every frame must list every node once, frames
/// contiguous with ascending times. Throws RegisterInputError naming the file and line.
physics::DisplacementSeries ReadDisplacementSeries(const std::filesystem::path& file,
                                                   const physics::TetrahedralMesh& rest);

}  // namespace vesica::app::registration
