#include "app/patient/patient_files.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkNIFTIImageReader.h>
#include <vtkNIFTIImageWriter.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkTypeInt16Array.h>
#include <vtkTypeUInt8Array.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "physics/patient/patient_labels.h"

namespace vesica::app::patient {
namespace fs = std::filesystem;
namespace {

// NIfTI's world is RAS (x right); ours is x left, y anterior, z cranial.
const Eigen::Matrix3d kRasFromOurs = Eigen::Vector3d(-1.0, 1.0, 1.0).asDiagonal();

[[noreturn]] void Fail(const fs::path& file, const std::string& why) {
  throw PatientFileError(file.string() + ": " + why);
}

vtkNew<vtkMatrix4x4> RasMatrix(const physics::LabelVolume& grid) {
  vtkNew<vtkMatrix4x4> m;
  const Eigen::Matrix3d rotation = kRasFromOurs * grid.direction;
  const Eigen::Vector3d offset = kRasFromOurs * grid.origin_m * 1000.0;  // NIfTI in millimetres
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) m->SetElement(r, c, rotation(r, c));
    m->SetElement(r, 3, offset(r));
  }
  return m;
}

vtkNew<vtkImageData> ImageOf(const physics::LabelVolume& grid, vtkDataArray* scalars) {
  vtkNew<vtkImageData> image;
  image->SetDimensions(grid.dims[0], grid.dims[1], grid.dims[2]);
  image->SetSpacing(grid.spacing_m.x() * 1000.0, grid.spacing_m.y() * 1000.0, grid.spacing_m.z() * 1000.0);
  image->SetOrigin(0.0, 0.0, 0.0);
  image->GetPointData()->SetScalars(scalars);
  return image;
}

void Write(vtkImageData* image, const physics::LabelVolume& grid, const fs::path& file) {
  vtkNew<vtkNIFTIImageWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(file.string().c_str());
  vtkNew<vtkMatrix4x4> ras = RasMatrix(grid);
  writer->SetQFormMatrix(ras);
  writer->SetSFormMatrix(ras);
  writer->Write();
  if (writer->GetErrorCode() != 0 || !fs::exists(file)) Fail(file, "cannot be written");
}

struct ReadImage {
  vtkSmartPointer<vtkImageData> image;
  physics::LabelVolume grid;  // without labels
};

ReadImage Read(const fs::path& file) {
  if (!fs::exists(file)) Fail(file, "no such file");
  vtkNew<vtkNIFTIImageReader> reader;
  if (!reader->CanReadFile(file.string().c_str())) Fail(file, "is not a NIfTI file");
  reader->SetFileName(file.string().c_str());
  reader->Update();
  ReadImage out;
  out.image = reader->GetOutput();
  int dims[3];
  out.image->GetDimensions(dims);
  if (reader->GetErrorCode() != 0 || dims[0] < 1 || dims[1] < 1 || dims[2] < 1 ||
      !out.image->GetPointData()->GetScalars())
    Fail(file, "cannot be read (truncated or damaged)");
  if (reader->GetTimeDimension() > 1)
    Fail(file, "has " + std::to_string(reader->GetTimeDimension()) + " time points; a CT has one");
  if (out.image->GetNumberOfScalarComponents() != 1) Fail(file, "has more than one value per voxel");
  double spacing[3], origin[3];
  out.image->GetSpacing(spacing);
  out.image->GetOrigin(origin);
  vtkMatrix4x4* m = reader->GetSFormMatrix() ? reader->GetSFormMatrix() : reader->GetQFormMatrix();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  if (m) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) rotation(r, c) = m->GetElement(r, c);
      offset(r) = m->GetElement(r, 3);
    }
  }
  if ((rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).norm() > 1e-4)
    Fail(file, "its orientation matrix is not a rotation (sheared or scaled sform)");
  out.grid.dims = {dims[0], dims[1], dims[2]};
  for (int c = 0; c < 3; ++c) {
    if (!(spacing[c] > 0.0)) Fail(file, "has a voxel size of " + std::to_string(spacing[c]) + " mm");
    out.grid.spacing_m(c) = spacing[c] / 1000.0;
  }
  out.grid.direction = kRasFromOurs * rotation;
  out.grid.origin_m = kRasFromOurs * (rotation * Eigen::Vector3d(origin[0], origin[1], origin[2]) + offset) / 1000.0;
  return out;
}

}  // namespace

void WriteNiftiPatient(const PatientVolume& patient, const fs::path& volume_file, const fs::path& labels_file) {
  const physics::LabelVolume& grid = patient.labels;
  const std::size_t n = grid.labels.size();
  if (patient.hu.size() != n) throw std::invalid_argument("patient volume: HU and labels differ in size");
  vtkNew<vtkTypeInt16Array> hu;
  hu->SetNumberOfTuples(static_cast<vtkIdType>(n));
  std::copy(patient.hu.begin(), patient.hu.end(), hu->GetPointer(0));
  vtkNew<vtkTypeUInt8Array> labels;
  labels->SetNumberOfTuples(static_cast<vtkIdType>(n));
  std::copy(grid.labels.begin(), grid.labels.end(), labels->GetPointer(0));
  Write(ImageOf(grid, hu), grid, volume_file);
  Write(ImageOf(grid, labels), grid, labels_file);
}

PatientVolume ReadNiftiVolume(const fs::path& file) {
  ReadImage read = Read(file);
  PatientVolume out;
  out.labels = read.grid;
  vtkDataArray* scalars = read.image->GetPointData()->GetScalars();
  out.hu.resize(static_cast<std::size_t>(scalars->GetNumberOfTuples()));
  for (vtkIdType q = 0; q < scalars->GetNumberOfTuples(); ++q)
    out.hu[static_cast<std::size_t>(q)] =
        static_cast<std::int16_t>(std::clamp(std::round(scalars->GetComponent(q, 0)), -32768.0, 32767.0));
  return out;
}

physics::LabelVolume ReadNiftiLabels(const fs::path& file) {
  ReadImage read = Read(file);
  vtkDataArray* scalars = read.image->GetPointData()->GetScalars();
  read.grid.labels.resize(static_cast<std::size_t>(scalars->GetNumberOfTuples()));
  for (vtkIdType q = 0; q < scalars->GetNumberOfTuples(); ++q) {
    const double v = scalars->GetComponent(q, 0);
    if (v < 0.0 || v > 255.0 || v != std::floor(v))
      Fail(file, "label " + std::to_string(v) + " at voxel " + std::to_string(q) + " is not an integer 0-255");
    read.grid.labels[static_cast<std::size_t>(q)] = static_cast<std::uint8_t>(v);
  }
  return read.grid;
}

void CheckSameGrid(const physics::LabelVolume& a, const std::string& a_name, const physics::LabelVolume& b,
                   const std::string& b_name) {
  const std::string both = a_name + " and " + b_name;
  const auto dims = [](const physics::LabelVolume& v) {
    return std::to_string(v.dims[0]) + " x " + std::to_string(v.dims[1]) + " x " + std::to_string(v.dims[2]);
  };
  if (a.dims != b.dims) throw PatientFileError(both + ": sizes differ (" + dims(a) + " vs " + dims(b) + " voxels)");
  const auto mm = [](const Eigen::Vector3d& s) {
    std::ostringstream o;
    o << 1000 * s.x() << " x " << 1000 * s.y() << " x " << 1000 * s.z() << " mm";
    return o.str();
  };
  if ((a.spacing_m - b.spacing_m).norm() > 1e-6)
    throw PatientFileError(both + ": voxel sizes differ (" + mm(a.spacing_m) + " vs " + mm(b.spacing_m) + ")");
  if ((a.direction - b.direction).norm() > 1e-4) throw PatientFileError(both + ": orientations differ");
  if ((a.origin_m - b.origin_m).norm() > 1e-5) throw PatientFileError(both + ": origins differ");
}

void RemapLabels(physics::LabelVolume& labels, const LabelTable& table, const std::string& labels_name) {
  const std::map<int, std::uint8_t> remap = RemapToTrainer(table);
  std::array<int, 256> to{};
  to.fill(-1);
  for (const auto& [from, value] : remap) to[static_cast<std::size_t>(from)] = value;
  std::map<int, long> unknown;
  bool liver = false;
  for (std::uint8_t& l : labels.labels) {
    const int mapped = to[l];
    if (mapped < 0) {
      ++unknown[l];
      continue;
    }
    l = static_cast<std::uint8_t>(mapped);
    liver = liver || physics::patient_label::IsLiver(l);
  }
  if (!unknown.empty()) {
    std::string list;
    for (const auto& [value, count] : unknown)
      list += (list.empty() ? "" : ", ") + std::to_string(value) + " (" + std::to_string(count) + " voxels)";
    throw PatientFileError(labels_name + ": labels not in the label table: " + list);
  }
  if (!liver) throw PatientFileError(labels_name + ": the label map has no liver");
}

PatientVolume LoadNiftiPatient(const fs::path& volume_file, const fs::path& labels_file, const fs::path& table_file) {
  LabelTable table;
  try {
    table = ReadLabelTable(table_file);
  } catch (const std::runtime_error& e) {
    throw PatientFileError(e.what());
  }
  PatientVolume patient = ReadNiftiVolume(volume_file);
  physics::LabelVolume labels = ReadNiftiLabels(labels_file);
  CheckSameGrid(patient.labels, volume_file.string(), labels, labels_file.string());
  RemapLabels(labels, table, labels_file.string());
  patient.labels = std::move(labels);
  return patient;
}

}  // namespace vesica::app::patient
