#pragma once
// The biopsy patient as the needle mode holds it, built once and shared (const): the CT and its
// label map, the breathing model (issue 33) and the CT as the needle samples it through the
// breathing (issue 34). Loading the synthetic patient and building both models take a few seconds.

#include <filesystem>
#include <memory>

#include "app/patient/patient_volume.h"
#include "physics/needle/deformed_ct.h"
#include "physics/patient/breathing_patient_model.h"

namespace vesica::app::biopsy {

struct BiopsyPatient {
  patient::PatientVolume volume;
  std::shared_ptr<const physics::BreathingPatientModel> model;
  std::shared_ptr<const physics::DeformedCtModel> ct;
};

/// Builds both models for a loaded volume. Throws std::invalid_argument (the model's reason).
std::shared_ptr<const BiopsyPatient> MakeBiopsyPatient(patient::PatientVolume volume);

/// The committed patient: `<folder>/synthetic-biopsy_ct.nii.gz`, `_labels.nii.gz` and
/// `_labels.toml`. Throws patient::PatientFileError naming the file.
std::shared_ptr<const BiopsyPatient> LoadCommittedBiopsyPatient(const std::filesystem::path& folder);

}  // namespace vesica::app::biopsy
