#include "app/biopsy/liver_motion.h"

#include "app/mesh_io/mesh_io.h"
#include "app/register/displacement_csv.h"
#include "physics/registration/displacement_series.h"

namespace vesica::app::biopsy {

physics::BreathingPatient::LiverMotion LoadLiverMotion(const BiopsyPatient& patient, const std::filesystem::path& mesh,
                                                       const std::filesystem::path& displacement_csv) {
  const physics::TetrahedralMesh rest = ReadTetrahedralMesh(mesh);
  auto series =
      std::make_shared<const physics::DisplacementSeries>(registration::ReadDisplacementSeries(displacement_csv, rest));
  return physics::MakePointMotion(std::move(series), patient.model->liver.lattice.rest_m);
}

}  // namespace vesica::app::biopsy
