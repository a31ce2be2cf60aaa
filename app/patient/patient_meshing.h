#pragma once
// Meshing of a patient's label map (seed section 3.3): per organ, marching cubes on its labels
// (VTK's discrete flying edges), smoothing and decimation. The surfaces are for rendering; the
// deformable organs (diaphragm, liver) move with their ChainMail lattices (physics/patient),
// their vertices carried by LatticeEmbedding.

#include <cstdint>
#include <string>
#include <vector>

#include "physics/mesh/triangle_mesh.h"
#include "physics/patient/label_volume.h"

namespace vesica::app::patient {

struct MeshingOptions {
  double decimate_fraction = 0.5;  ///< share of triangles removed (topology kept)
  int smoothing_iterations = 15;   ///< windowed-sinc smoothing of the marching-cubes mesh
  double smoothing_passband = 0.1;
};

struct OrganSurface {
  std::string organ;                 ///< e.g. "liver", "rib_r7"
  std::vector<std::uint8_t> labels;  ///< the label values it encloses
  physics::TriangleMesh mesh;        ///< world metres
};

/// One organ's surface: the boundary of the voxels whose label is in `labels`. Throws
/// std::invalid_argument naming the organ when it has no voxel.
[[nodiscard]] physics::TriangleMesh MeshLabels(const physics::LabelVolume& volume,
                                               const std::vector<std::uint8_t>& labels, const std::string& organ,
                                               const MeshingOptions& options = {});

/// The surfaces the biopsy scene draws: skin, lungs, diaphragm, liver (capsule and tumour inside),
/// tumour, gallbladder, colon, spine, sternum, each rib with its cartilage; organs absent from the
/// label map are left out.
[[nodiscard]] std::vector<OrganSurface> MeshPatient(const physics::LabelVolume& volume,
                                                    const MeshingOptions& options = {});

}  // namespace vesica::app::patient
