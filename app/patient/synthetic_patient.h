#pragma once
// The synthetic biopsy patient (issue 33): an adult's thorax and upper abdomen as a CT in
// Hounsfield units with its label map, made from analytic shapes, deterministic (no noise, no
// random numbers). docs/biopsy-patient.md lists each proportion and where it comes from.
//
// World frame as everywhere in Vesica: x to the patient's left, y anterior, z cranial, metres.
// The grid runs i to the patient's right, j anterior, k cranial (RAS, as NIfTI stores it).

#include "app/patient/patient_volume.h"

namespace vesica::app::patient {

struct SyntheticPatientOptions {
  double spacing_m = 0.002;  ///< isotropic voxel size; 1-4 mm
};

/// Generates the volume. Throws std::invalid_argument for a spacing outside 1-4 mm and
/// std::logic_error if a self-check of the anatomy fails (the tumour must lie inside the liver).
[[nodiscard]] PatientVolume GenerateSyntheticPatient(const SyntheticPatientOptions& options = {});

/// The tumour's centre and radius in the synthetic patient (seed 6.3: a 15 mm sphere).
struct SyntheticTumour {
  double x_m = -0.075, y_m = 0.02, z_m = -0.045, radius_m = 0.0075;
};

}  // namespace vesica::app::patient
