// vesica-patient: writes the synthetic liver-biopsy patient (data/patients/, docs/biopsy-patient.md):
// the CT in Hounsfield units, its label map and the label table. Deterministic.
#include <CLI/CLI.hpp>
#include <array>
#include <chrono>
#include <exception>
#include <filesystem>
#include <iostream>

#include "app/patient/label_table.h"
#include "app/patient/patient_files.h"
#include "app/patient/synthetic_patient.h"
#include "physics/patient/breathing_patient_model.h"

int main(int argc, char** argv) {
  namespace patient = vesica::app::patient;
  CLI::App cli{"Writes the synthetic liver-biopsy patient, deterministically (see docs/biopsy-patient.md)."};
  std::string output_dir = "data/patients";
  cli.add_option("-o,--output", output_dir, "directory to write the volume, label map and label table into");
  double spacing_mm = 2.0;
  cli.add_option("--spacing-mm", spacing_mm, "isotropic voxel size")->check(CLI::Range(1.0, 4.0));
  CLI11_PARSE(cli, argc, argv);
  try {
    const auto start = std::chrono::steady_clock::now();
    const patient::PatientVolume volume = patient::GenerateSyntheticPatient({.spacing_m = spacing_mm / 1000.0});
    const std::filesystem::path dir(output_dir);
    std::filesystem::create_directories(dir);
    patient::WriteNiftiPatient(volume, dir / "synthetic-biopsy_ct.nii.gz", dir / "synthetic-biopsy_labels.nii.gz");
    patient::WriteLabelTable(patient::TrainerLabelTable(), dir / "synthetic-biopsy_labels.toml",
                             "Label table of synthetic-biopsy_labels.nii.gz (written by vesica-patient).\n"
                             "value: the voxel value in the label map; name: the structure (docs/biopsy-patient.md).");
    const auto model = vesica::physics::BuildBreathingPatientModel(volume.labels);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    std::array<long, 256> count{};
    for (std::uint8_t l : volume.labels.labels) ++count[l];
    const double ml = volume.labels.VoxelVolume_m3() * 1e6;
    std::cout << "grid " << volume.labels.dims[0] << " x " << volume.labels.dims[1] << " x " << volume.labels.dims[2]
              << " voxels of " << spacing_mm << " mm\n";
    for (int l = 1; l < 20; ++l)
      if (count[static_cast<std::size_t>(l)] > 0)
        std::cout << "  " << patient::NameOfLabelValue(static_cast<std::uint8_t>(l)) << ": "
                  << count[static_cast<std::size_t>(l)] * ml << " ml\n";
    std::cout << "ribs " << model->ribs.size() << "; diaphragm lattice " << model->diaphragm.lattice.size()
              << " elements, tendon " << model->diaphragm.tendon.size() << ", fixed at the spine "
              << model->diaphragm.spine_attachment.size() << ", tendon travel before the crura move "
              << model->diaphragm.max_tendon_displacement_m * 1000 << " mm; liver lattice "
              << model->liver.lattice.size() << " elements, " << model->liver.coupling.size()
              << " coupled to the diaphragm\n"
              << "written to " << output_dir << " in " << seconds << " s\n";
  } catch (const std::exception& e) {
    std::cerr << "vesica-patient: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
