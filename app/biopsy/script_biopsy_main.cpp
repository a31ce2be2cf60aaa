// vesica-script-biopsy: writes the committed recorded biopsy (a stylus stream, docs/needle-mode.md)
// for the committed synthetic patient.
//   vesica-script-biopsy [-o data/recordings/biopsy.csv] [--patient-dir data/patients]

#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

#include "app/biopsy/biopsy_patient.h"
#include "app/biopsy/scripted_biopsy.h"

int main(int argc, char** argv) {
  CLI::App cli{"Vesica: write the scripted needle biopsy as a stylus recording"};
  std::string output = std::string(VESICA_DATA_DIR) + "/recordings/biopsy.csv";
  std::string patient_dir = std::string(VESICA_DATA_DIR) + "/patients";
  cli.add_option("-o,--output", output, "recording to write")->capture_default_str();
  cli.add_option("--patient-dir", patient_dir, "folder of the synthetic patient's files")->capture_default_str();
  CLI11_PARSE(cli, argc, argv);
  try {
    using namespace vesica::app::biopsy;
    const auto patient = LoadCommittedBiopsyPatient(patient_dir);
    const StylusPlacement placement = PlacementAtRightSide(patient->model->liver.tumour_centre_m);
    const auto recording = ScriptBiopsy(placement);
    vesica::device::WriteStylusRecording(output, recording);
    std::cout << "wrote " << output << ": " << recording.samples.size() << " samples, "
              << recording.samples.back().time_s << " s\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "vesica-script-biopsy: " << e.what() << '\n';
    return 1;
  }
}
