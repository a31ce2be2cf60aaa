#pragma once
// Reading and writing a patient's CT and label map (issue 33): NIfTI (.nii, .nii.gz, as ITK-SNAP
// writes them) through VTK's NIfTI reader and writer, orientation from the sform (else the qform),
// and the label table that names each label. Every error names the file it is about.

#include <filesystem>
#include <stdexcept>
#include <string>

#include "app/patient/label_table.h"
#include "app/patient/patient_volume.h"

namespace vesica::app::patient {

/// A patient file that cannot be used; what() names the file and the reason.
class PatientFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Writes the volume (int16 HU) and the label map (uint8, trainer values) as NIfTI-1 with qform and
/// sform (scanner RAS), gzip'd when the name ends in .gz.
void WriteNiftiPatient(const PatientVolume& patient, const std::filesystem::path& volume_file,
                       const std::filesystem::path& labels_file);

/// A CT volume alone (HU; other integer or float types are rounded and clamped to int16). The
/// returned labels hold the grid and an empty label vector.
[[nodiscard]] PatientVolume ReadNiftiVolume(const std::filesystem::path& file);
/// A label map alone, values as stored (0-255, else an error).
[[nodiscard]] physics::LabelVolume ReadNiftiLabels(const std::filesystem::path& file);

/// Volume + label map + label table: checks that both grids agree (size, spacing, orientation,
/// origin), that every value in the label map has a row in the table, and that there is a liver;
/// the labels come back as the trainer's values.
[[nodiscard]] PatientVolume LoadNiftiPatient(const std::filesystem::path& volume_file,
                                             const std::filesystem::path& labels_file,
                                             const std::filesystem::path& table_file);

/// The same checks for grids read some other way (DICOM): throws PatientFileError naming both.
void CheckSameGrid(const physics::LabelVolume& a, const std::string& a_name, const physics::LabelVolume& b,
                   const std::string& b_name);
/// Remaps a label map to trainer values through a table; unknown values and a missing liver are
/// errors naming labels_name.
void RemapLabels(physics::LabelVolume& labels, const LabelTable& table, const std::string& labels_name);

}  // namespace vesica::app::patient
