#pragma once
// A CT as a DICOM series (one file a slice), read through VTK's DICOM reader slice by slice so
// that each slice's position is checked: the series must have one size, one orientation and one
// pixel spacing, and evenly spaced slices (a gap means a missing slice). Errors name the file.
// The writer makes a minimal CT series (explicit VR little endian) from a volume; it is what the
// round-trip test reads back.

#include <filesystem>

#include "app/patient/label_table.h"
#include "app/patient/patient_volume.h"

namespace vesica::app::patient {

/// Every regular file in `directory` is a slice. HU = stored value * slope + intercept.
/// Throws PatientFileError.
[[nodiscard]] PatientVolume ReadDicomSeries(const std::filesystem::path& directory);

/// A DICOM series + NIfTI label map + label table, checked as LoadNiftiPatient.
[[nodiscard]] PatientVolume LoadDicomPatient(const std::filesystem::path& directory,
                                             const std::filesystem::path& labels_file,
                                             const std::filesystem::path& table_file);

/// Writes slice_0000.dcm ... into `directory` (created), one per k.
void WriteDicomSeries(const PatientVolume& volume, const std::filesystem::path& directory);

}  // namespace vesica::app::patient
