// The patient's files (issue 33): the committed synthetic patient is what vesica-patient makes,
// NIfTI round trips keep voxels, grid and orientation, and each bad file gets an error naming it.
#include "app/patient/patient_files.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>

#include "app/patient/label_table.h"
#include "app/patient/synthetic_patient.h"
#include "physics/patient/patient_labels.h"

namespace vesica::app::patient {
namespace {
namespace fs = std::filesystem;
namespace label = physics::patient_label;

const fs::path kData = fs::path(VESICA_SOURCE_DIR) / "data" / "patients";

const PatientVolume& Synthetic() {
  static const PatientVolume volume = GenerateSyntheticPatient();
  return volume;
}

fs::path Scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("vesica-patient-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

std::string ErrorOf(const auto& load) {
  try {
    load();
  } catch (const PatientFileError& e) {
    return e.what();
  }
  return "no error";
}

void ExpectSameGrid(const physics::LabelVolume& a, const physics::LabelVolume& b) {
  EXPECT_EQ(a.dims, b.dims);
  EXPECT_LT((a.spacing_m - b.spacing_m).norm(), 1e-9);
  EXPECT_LT((a.direction - b.direction).norm(), 1e-6);
  EXPECT_LT((a.origin_m - b.origin_m).norm(), 1e-8);
}

TEST(PatientFilesTest, CommittedPatientIsWhatTheGeneratorMakes) {
  const PatientVolume loaded =
      LoadNiftiPatient(kData / "synthetic-biopsy_ct.nii.gz", kData / "synthetic-biopsy_labels.nii.gz",
                       kData / "synthetic-biopsy_labels.toml");
  ExpectSameGrid(loaded.labels, Synthetic().labels);
  EXPECT_TRUE(loaded.labels.labels == Synthetic().labels.labels);
  EXPECT_TRUE(loaded.hu == Synthetic().hu);
  // Small enough for the repository.
  EXPECT_LT(
      fs::file_size(kData / "synthetic-biopsy_ct.nii.gz") + fs::file_size(kData / "synthetic-biopsy_labels.nii.gz"),
      2'000'000u);
}

TEST(PatientFilesTest, SyntheticPatientIsAnAdultsAnatomy) {
  const physics::LabelVolume& v = Synthetic().labels;
  std::array<long, 256> count{};
  for (std::uint8_t l : v.labels) ++count[l];
  const double ml = v.VoxelVolume_m3() * 1e6;
  const double liver_ml = (count[label::kLiver] + count[label::kLiverCapsule] + count[label::kTumour]) * ml;
  EXPECT_GT(liver_ml, 1200.0);  // adult liver 1.2-1.9 l
  EXPECT_LT(liver_ml, 1900.0);
  EXPECT_NEAR(count[label::kTumour] * ml, 4.0 / 3.0 * M_PI * 0.75 * 0.75 * 0.75, 0.2);  // 15 mm sphere
  for (int n = 1; n <= 12; ++n)
    for (bool left : {false, true}) {
      EXPECT_GT(count[label::Rib(left, n)], 0) << n;
      EXPECT_GT(count[label::Cartilage(left, n)], 0) << n;
      EXPECT_GT(count[label::Bundle(left, n)], 0) << n;
    }
  for (std::uint8_t l : {label::kSkin, label::kFat, label::kMuscle, label::kSpine, label::kSternum, label::kLung,
                         label::kCostophrenicRecess, label::kDiaphragmMuscle, label::kDiaphragmTendon,
                         label::kGallbladder, label::kColon})
    EXPECT_GT(count[l], 0) << int(l);
  // Hounsfield units: air outside, lung, fat, liver, bone.
  const auto hu_of = [&](std::uint8_t l) {
    for (std::size_t q = 0; q < v.labels.size(); ++q)
      if (v.labels[q] == l) return Synthetic().hu[q];
    return std::int16_t(0);
  };
  EXPECT_EQ(hu_of(label::kAir), -1000);
  EXPECT_EQ(hu_of(label::kLung), -850);
  EXPECT_EQ(hu_of(label::kFat), -100);
  EXPECT_EQ(hu_of(label::kLiver), 60);
  EXPECT_EQ(hu_of(label::Rib(false, 8)), 700);
}

TEST(PatientFilesTest, NiftiRoundTripKeepsVoxelsAndOrientation) {
  // An oblique grid: turned 30 degrees about the body axis and moved.
  PatientVolume turned = GenerateSyntheticPatient({.spacing_m = 0.004});
  turned.labels.direction =
      Eigen::AngleAxisd(M_PI / 6, Eigen::Vector3d::UnitZ()).toRotationMatrix() * turned.labels.direction;
  turned.labels.origin_m += Eigen::Vector3d(0.01, -0.02, 0.3);
  const fs::path ct = Scratch("turned_ct.nii.gz"), labels = Scratch("turned_labels.nii");
  WriteNiftiPatient(turned, ct, labels);
  const PatientVolume read = ReadNiftiVolume(ct);
  const physics::LabelVolume read_labels = ReadNiftiLabels(labels);
  ExpectSameGrid(read.labels, turned.labels);
  ExpectSameGrid(read_labels, turned.labels);
  EXPECT_TRUE(read.hu == turned.hu);
  EXPECT_TRUE(read_labels.labels == turned.labels.labels);
  // A voxel lands at the same place in the world.
  EXPECT_LT((read_labels.Position(10, 20, 30) - turned.labels.Position(10, 20, 30)).norm(), 1e-8);
}

TEST(PatientFilesTest, BadFilesAreNamed) {
  const PatientVolume small = GenerateSyntheticPatient({.spacing_m = 0.004});
  const fs::path ct = Scratch("small_ct.nii.gz"), labels = Scratch("small_labels.nii.gz");
  WriteNiftiPatient(small, ct, labels);
  const fs::path table = kData / "synthetic-biopsy_labels.toml";
  ASSERT_NO_THROW((void)LoadNiftiPatient(ct, labels, table));

  const std::string missing = ErrorOf([&] { (void)LoadNiftiPatient(Scratch("none.nii.gz"), labels, table); });
  EXPECT_NE(missing.find("none.nii.gz: no such file"), std::string::npos) << missing;

  const fs::path text = Scratch("text.nii");
  std::ofstream(text) << "not an image\n";
  const std::string not_nifti = ErrorOf([&] { (void)LoadNiftiPatient(text, labels, table); });
  EXPECT_NE(not_nifti.find("text.nii"), std::string::npos) << not_nifti;

  const std::string sizes =
      ErrorOf([&] { (void)LoadNiftiPatient(kData / "synthetic-biopsy_ct.nii.gz", labels, table); });
  EXPECT_NE(sizes.find("sizes differ"), std::string::npos) << sizes;
  EXPECT_NE(sizes.find("small_labels.nii.gz"), std::string::npos) << sizes;

  PatientVolume stretched = small;
  stretched.labels.spacing_m.z() = 0.005;
  const fs::path ct2 = Scratch("stretched_ct.nii.gz"), labels2 = Scratch("stretched_labels.nii.gz");
  WriteNiftiPatient(stretched, ct2, labels2);
  const std::string spacing = ErrorOf([&] { (void)LoadNiftiPatient(ct, labels2, table); });
  EXPECT_NE(spacing.find("voxel sizes differ"), std::string::npos) << spacing;

  PatientVolume unknown = small;
  unknown.labels.labels[1234] = 200;
  const fs::path ct3 = Scratch("unknown_ct.nii.gz"), labels3 = Scratch("unknown_labels.nii.gz");
  WriteNiftiPatient(unknown, ct3, labels3);
  const std::string unknown_label = ErrorOf([&] { (void)LoadNiftiPatient(ct3, labels3, table); });
  EXPECT_NE(unknown_label.find("unknown_labels.nii.gz: labels not in the label table: 200 (1 voxels)"),
            std::string::npos)
      << unknown_label;

  PatientVolume no_liver = small;
  for (std::uint8_t& l : no_liver.labels.labels)
    if (label::IsLiver(l)) l = label::kSoftTissue;
  const fs::path ct4 = Scratch("noliver_ct.nii.gz"), labels4 = Scratch("noliver_labels.nii.gz");
  WriteNiftiPatient(no_liver, ct4, labels4);
  const std::string liver = ErrorOf([&] { (void)LoadNiftiPatient(ct4, labels4, table); });
  EXPECT_NE(liver.find("noliver_labels.nii.gz: the label map has no liver"), std::string::npos) << liver;
}

TEST(PatientFilesTest, LabelTablesAreCheckedAndRemapped) {
  const fs::path bad_name = Scratch("bad_name.toml");
  std::ofstream(bad_name) << "[[label]]\nvalue = 1\nname = \"livr\"\n";
  const std::string name = ErrorOf([&] {
    (void)LoadNiftiPatient(kData / "synthetic-biopsy_ct.nii.gz", kData / "synthetic-biopsy_labels.nii.gz", bad_name);
  });
  EXPECT_NE(name.find("bad_name.toml, label entry 1: unknown structure name 'livr'"), std::string::npos) << name;
  const fs::path twice = Scratch("twice.toml");
  std::ofstream(twice) << "[[label]]\nvalue = 1\nname = \"liver\"\n[[label]]\nvalue = 1\nname = \"lung\"\n";
  EXPECT_THROW((void)ReadLabelTable(twice), std::runtime_error);
  // An ITK-SNAP style table: 1 is the liver, 2 the diaphragm's tendon.
  const fs::path itk = Scratch("itk.toml");
  std::ofstream(itk) << "[[label]]\nvalue = 0\nname = \"air\"\n[[label]]\nvalue = 1\nname = \"liver\"\n"
                        "[[label]]\nvalue = 2\nname = \"diaphragm_tendon\"\n";
  physics::LabelVolume map;
  map.dims = {2, 2, 1};
  map.labels = {0, 1, 2, 1};
  RemapLabels(map, ReadLabelTable(itk), "itk_labels.nii.gz");
  EXPECT_EQ(map.labels,
            (std::vector<std::uint8_t>{label::kAir, label::kLiver, label::kDiaphragmTendon, label::kLiver}));
}

}  // namespace
}  // namespace vesica::app::patient
