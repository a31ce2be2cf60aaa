#pragma once
// A patient's CT as the biopsy trainer holds it: Hounsfield units and the label map on one grid
// (issue 33). Both come from the synthetic generator or from NIfTI / DICOM files.

#include <cstdint>
#include <vector>

#include "physics/patient/label_volume.h"

namespace vesica::app::patient {

struct PatientVolume {
  physics::LabelVolume labels;   ///< grid, orientation and the label of each voxel
  std::vector<std::int16_t> hu;  ///< Hounsfield units, same grid (i fastest)
};

}  // namespace vesica::app::patient
