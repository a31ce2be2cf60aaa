#pragma once
// A registration result as the biopsy patient's breathing (issue 35): vesica-register's
// displacement.csv on the tet mesh it registered, replayed on the liver's lattice elements in
// place of ChainMail (BiopsySessionSettings::liver_motion), so a measured breathing motion can
// be rehearsed on the patient.

#include <filesystem>

#include "app/biopsy/biopsy_patient.h"
#include "physics/patient/breathing_patient.h"

namespace vesica::app::biopsy {

/// Reads the mesh (.vtu/.vtk) and the series (displacement.csv) and binds the patient's liver
/// elements to it. Throws (RegisterInputError, MeshIoError, std::invalid_argument) naming the file.
physics::BreathingPatient::LiverMotion LoadLiverMotion(const BiopsyPatient& patient, const std::filesystem::path& mesh,
                                                       const std::filesystem::path& displacement_csv);

}  // namespace vesica::app::biopsy
