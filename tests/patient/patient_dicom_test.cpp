// DICOM series (issue 33): a series made from the synthetic volume loads to the same voxels and
// grid; a missing slice, a slice of another size and a non-DICOM file are named.
#include "app/patient/patient_dicom.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "app/patient/patient_files.h"
#include "app/patient/synthetic_patient.h"

namespace vesica::app::patient {
namespace {
namespace fs = std::filesystem;

fs::path Scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("vesica-dicom-test-" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string ErrorOf(const auto& load) {
  try {
    load();
  } catch (const PatientFileError& e) {
    return e.what();
  }
  return "no error";
}

const PatientVolume& Small() {
  static const PatientVolume volume = GenerateSyntheticPatient({.spacing_m = 0.004});
  return volume;
}

TEST(PatientDicomTest, SeriesLoadsToTheSameVoxels) {
  const fs::path dir = Scratch("series");
  WriteDicomSeries(Small(), dir);
  const PatientVolume read = ReadDicomSeries(dir);
  EXPECT_EQ(read.labels.dims, Small().labels.dims);
  EXPECT_LT((read.labels.spacing_m - Small().labels.spacing_m).norm(), 1e-9);
  EXPECT_LT((read.labels.direction - Small().labels.direction).norm(), 1e-6);
  EXPECT_LT((read.labels.origin_m - Small().labels.origin_m).norm(), 1e-6);
  EXPECT_TRUE(read.hu == Small().hu);
  // With the label map written as NIfTI: the grids agree and the labels load.
  const fs::path labels = dir.parent_path() / "labels.nii.gz";
  WriteNiftiPatient(Small(), dir.parent_path() / "ct.nii.gz", labels);
  const PatientVolume patient =
      LoadDicomPatient(dir, labels, fs::path(VESICA_SOURCE_DIR) / "data" / "patients" / "synthetic-biopsy_labels.toml");
  EXPECT_TRUE(patient.labels.labels == Small().labels.labels);
}

TEST(PatientDicomTest, BadSeriesAreNamed) {
  const fs::path dir = Scratch("missing");
  WriteDicomSeries(Small(), dir);
  fs::remove(dir / "slice_0040.dcm");
  const std::string missing = ErrorOf([&] { (void)ReadDicomSeries(dir); });
  EXPECT_NE(missing.find("missing or uneven slices between slice_0039.dcm and slice_0041.dcm"), std::string::npos)
      << missing;

  const fs::path other = Scratch("other");
  WriteDicomSeries(Small(), other);
  PatientVolume wider = GenerateSyntheticPatient({.spacing_m = 0.003});
  const fs::path wide = Scratch("wide");
  WriteDicomSeries(wider, wide);
  fs::copy_file(wide / "slice_0003.dcm", other / "slice_0003.dcm", fs::copy_options::overwrite_existing);
  const std::string size = ErrorOf([&] { (void)ReadDicomSeries(other); });
  EXPECT_NE(size.find("slice_0003.dcm: slice of 120 x 87 pixels in a series of 90 x 65"), std::string::npos) << size;

  const fs::path junk = Scratch("junk");
  WriteDicomSeries(Small(), junk);
  std::ofstream(junk / "slice_0002.dcm") << "not DICOM";
  const std::string not_dicom = ErrorOf([&] { (void)ReadDicomSeries(junk); });
  EXPECT_NE(not_dicom.find("slice_0002.dcm"), std::string::npos) << not_dicom;

  const std::string none = ErrorOf([&] { (void)ReadDicomSeries(Scratch("empty") / "nothing"); });
  EXPECT_NE(none.find("nothing: no such directory"), std::string::npos) << none;
}

}  // namespace
}  // namespace vesica::app::patient
