#include "app/biopsy/biopsy_patient.h"

#include "app/patient/patient_files.h"

namespace vesica::app::biopsy {

std::shared_ptr<const BiopsyPatient> MakeBiopsyPatient(patient::PatientVolume volume) {
  auto patient = std::make_shared<BiopsyPatient>();
  patient->volume = std::move(volume);
  patient->model = physics::BuildBreathingPatientModel(patient->volume.labels);
  patient->ct = physics::BuildDeformedCtModel(patient->model, patient->volume.hu);
  return patient;
}

std::shared_ptr<const BiopsyPatient> LoadCommittedBiopsyPatient(const std::filesystem::path& folder) {
  return MakeBiopsyPatient(patient::LoadNiftiPatient(folder / "synthetic-biopsy_ct.nii.gz",
                                                     folder / "synthetic-biopsy_labels.nii.gz",
                                                     folder / "synthetic-biopsy_labels.toml"));
}

}  // namespace vesica::app::biopsy
