#include "app/patient/patient_dicom.h"

#include <vtkDICOMImageReader.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/patient/patient_files.h"

namespace vesica::app::patient {
namespace fs = std::filesystem;
namespace {

// DICOM's patient frame is LPS (x left, y posterior); ours is x left, y anterior.
const Eigen::Matrix3d kLpsFromOurs = Eigen::Vector3d(1.0, -1.0, 1.0).asDiagonal();

struct Slice {
  fs::path file;
  int columns = 0, rows = 0;
  Eigen::Vector3d position_mm, row_direction, column_direction;  // LPS
  double column_spacing_mm = 0, row_spacing_mm = 0;
  std::vector<std::int16_t> hu;  // row by row, DICOM order
};

Slice ReadSlice(const fs::path& file) {
  vtkNew<vtkDICOMImageReader> reader;
  if (!reader->CanReadFile(file.string().c_str())) throw PatientFileError(file.string() + ": is not a DICOM file");
  reader->SetFileName(file.string().c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  if (reader->GetErrorCode() != 0 || !scalars || dims[2] != 1 || dims[0] < 1 || dims[1] < 1)
    throw PatientFileError(file.string() + ": cannot be read as one DICOM slice");
  Slice s;
  s.file = file;
  s.columns = dims[0];
  s.rows = dims[1];
  const float* position = reader->GetImagePositionPatient();
  const float* orientation = reader->GetImageOrientationPatient();
  s.position_mm = Eigen::Vector3d(position[0], position[1], position[2]);
  s.row_direction = Eigen::Vector3d(orientation[0], orientation[1], orientation[2]);
  s.column_direction = Eigen::Vector3d(orientation[3], orientation[4], orientation[5]);
  if (std::abs(s.row_direction.norm() - 1) > 1e-3 || std::abs(s.column_direction.norm() - 1) > 1e-3 ||
      std::abs(s.row_direction.dot(s.column_direction)) > 1e-3)
    throw PatientFileError(file.string() + ": its image orientation is not two orthogonal unit vectors");
  const double* spacing = reader->GetPixelSpacing();
  s.column_spacing_mm = spacing[0];
  s.row_spacing_mm = spacing[1];
  const double slope = reader->GetRescaleSlope() == 0.0f ? 1.0 : reader->GetRescaleSlope();
  const double intercept = reader->GetRescaleOffset();
  // VTK's reader puts the last DICOM row first (its images start bottom left): undo that.
  s.hu.resize(static_cast<std::size_t>(s.rows) * s.columns);
  for (int r = 0; r < s.rows; ++r)
    for (int c = 0; c < s.columns; ++c) {
      const double stored = scalars->GetComponent(static_cast<vtkIdType>(s.rows - 1 - r) * s.columns + c, 0);
      s.hu[static_cast<std::size_t>(r) * s.columns + c] =
          static_cast<std::int16_t>(std::clamp(std::round(stored * slope + intercept), -32768.0, 32767.0));
    }
  return s;
}

// --- a minimal writer: explicit VR little endian ---
void Put16(std::string& out, std::uint16_t v) { out.append({char(v & 0xff), char(v >> 8)}); }
void Put32(std::string& out, std::uint32_t v) {
  for (int b = 0; b < 4; ++b) out.push_back(char((v >> (8 * b)) & 0xff));
}
void Element(std::string& out, std::uint16_t group, std::uint16_t element, const char* vr, std::string value) {
  const bool long_form = std::string(vr) == "OB" || std::string(vr) == "OW";
  if (value.size() % 2) value.push_back(std::string(vr) == "UI" ? '\0' : ' ');
  Put16(out, group);
  Put16(out, element);
  out.append(vr, 2);
  if (long_form) {
    Put16(out, 0);
    Put32(out, static_cast<std::uint32_t>(value.size()));
  } else {
    Put16(out, static_cast<std::uint16_t>(value.size()));
  }
  out += value;
}
std::string U16(std::uint16_t v) {
  std::string s;
  Put16(s, v);
  return s;
}
std::string Decimal(double v) {
  std::ostringstream o;
  o.precision(10);
  o << v;
  return o.str();
}

}  // namespace

PatientVolume ReadDicomSeries(const fs::path& directory) {
  if (!fs::is_directory(directory)) throw PatientFileError(directory.string() + ": no such directory");
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(directory))
    if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  if (files.size() < 2) throw PatientFileError(directory.string() + ": a DICOM series needs at least two slices");
  std::vector<Slice> slices;
  for (const fs::path& f : files) slices.push_back(ReadSlice(f));
  const Slice& first = slices.front();
  for (const Slice& s : slices) {
    if (s.rows != first.rows || s.columns != first.columns)
      throw PatientFileError(s.file.string() + ": slice of " + std::to_string(s.columns) + " x " +
                             std::to_string(s.rows) + " pixels in a series of " + std::to_string(first.columns) +
                             " x " + std::to_string(first.rows));
    if ((s.row_direction - first.row_direction).norm() > 1e-4 ||
        (s.column_direction - first.column_direction).norm() > 1e-4)
      throw PatientFileError(s.file.string() + ": its orientation differs from " + first.file.filename().string() +
                             "'s");
    if (std::abs(s.row_spacing_mm - first.row_spacing_mm) > 1e-4 ||
        std::abs(s.column_spacing_mm - first.column_spacing_mm) > 1e-4)
      throw PatientFileError(s.file.string() + ": its pixel spacing differs from " + first.file.filename().string() +
                             "'s");
  }
  const Eigen::Vector3d normal = first.row_direction.cross(first.column_direction);
  std::sort(slices.begin(), slices.end(),
            [&](const Slice& a, const Slice& b) { return a.position_mm.dot(normal) < b.position_mm.dot(normal); });
  double gap = INFINITY;
  for (std::size_t k = 1; k < slices.size(); ++k)
    gap = std::min(gap, (slices[k].position_mm - slices[k - 1].position_mm).dot(normal));
  if (!(gap > 1e-3)) throw PatientFileError(directory.string() + ": two slices at the same position");
  for (std::size_t k = 1; k < slices.size(); ++k) {
    const Eigen::Vector3d step = slices[k].position_mm - slices[k - 1].position_mm;
    if (std::abs(step.dot(normal) - gap) > 0.01 * gap || (step - step.dot(normal) * normal).norm() > 0.01 * gap)
      throw PatientFileError(directory.string() + ": missing or uneven slices between " +
                             slices[k - 1].file.filename().string() + " and " + slices[k].file.filename().string() +
                             " (" + Decimal(step.dot(normal)) + " mm apart, the series' spacing is " + Decimal(gap) +
                             " mm)");
  }
  PatientVolume out;
  physics::LabelVolume& grid = out.labels;
  grid.dims = {first.columns, first.rows, static_cast<int>(slices.size())};
  grid.spacing_m = Eigen::Vector3d(first.column_spacing_mm, first.row_spacing_mm, gap) / 1000.0;
  Eigen::Matrix3d lps;
  lps << first.row_direction, first.column_direction, normal;
  grid.direction = kLpsFromOurs * lps;  // kLpsFromOurs is its own inverse
  grid.origin_m = kLpsFromOurs * slices.front().position_mm / 1000.0;
  for (const Slice& s : slices) out.hu.insert(out.hu.end(), s.hu.begin(), s.hu.end());
  return out;
}

PatientVolume LoadDicomPatient(const fs::path& directory, const fs::path& labels_file, const fs::path& table_file) {
  LabelTable table;
  try {
    table = ReadLabelTable(table_file);
  } catch (const std::runtime_error& e) {
    throw PatientFileError(e.what());
  }
  PatientVolume patient = ReadDicomSeries(directory);
  physics::LabelVolume labels = ReadNiftiLabels(labels_file);
  CheckSameGrid(patient.labels, directory.string(), labels, labels_file.string());
  RemapLabels(labels, table, labels_file.string());
  patient.labels = std::move(labels);
  return patient;
}

void WriteDicomSeries(const PatientVolume& volume, const fs::path& directory) {
  const physics::LabelVolume& g = volume.labels;
  fs::create_directories(directory);
  const Eigen::Matrix3d lps = kLpsFromOurs * g.direction;
  if (lps.determinant() < 0.0) throw std::invalid_argument("DICOM series: the grid must be right-handed in LPS");
  const std::string uid_root = "1.2.826.0.1.3680043.10.1033.";  // a fixed, made-up root: deterministic files
  for (int k = 0; k < g.dims[2]; ++k) {
    const Eigen::Vector3d position = kLpsFromOurs * g.Position(0, 0, k) * 1000.0;
    std::string meta, data;
    const std::string sop = uid_root + "3." + std::to_string(k + 1);
    Element(meta, 0x0002, 0x0001, "OB", std::string("\0\1", 2));
    Element(meta, 0x0002, 0x0002, "UI", "1.2.840.10008.5.1.4.1.1.2");
    Element(meta, 0x0002, 0x0003, "UI", sop);
    Element(meta, 0x0002, 0x0010, "UI", "1.2.840.10008.1.2.1");
    Element(meta, 0x0002, 0x0012, "UI", uid_root + "0");
    Element(data, 0x0008, 0x0016, "UI", "1.2.840.10008.5.1.4.1.1.2");
    Element(data, 0x0008, 0x0018, "UI", sop);
    Element(data, 0x0008, 0x0060, "CS", "CT");
    Element(data, 0x0010, 0x0010, "PN", "Synthetic^Biopsy");
    Element(data, 0x0018, 0x0050, "DS", Decimal(g.spacing_m.z() * 1000));
    Element(data, 0x0020, 0x000D, "UI", uid_root + "1");
    Element(data, 0x0020, 0x000E, "UI", uid_root + "2");
    Element(data, 0x0020, 0x0013, "IS", std::to_string(k + 1));
    Element(data, 0x0020, 0x0032, "DS",
            Decimal(position.x()) + "\\" + Decimal(position.y()) + "\\" + Decimal(position.z()));
    Element(data, 0x0020, 0x0037, "DS",
            Decimal(lps(0, 0)) + "\\" + Decimal(lps(1, 0)) + "\\" + Decimal(lps(2, 0)) + "\\" + Decimal(lps(0, 1)) +
                "\\" + Decimal(lps(1, 1)) + "\\" + Decimal(lps(2, 1)));
    Element(data, 0x0028, 0x0002, "US", U16(1));
    Element(data, 0x0028, 0x0004, "CS", "MONOCHROME2");
    Element(data, 0x0028, 0x0010, "US", U16(static_cast<std::uint16_t>(g.dims[1])));
    Element(data, 0x0028, 0x0011, "US", U16(static_cast<std::uint16_t>(g.dims[0])));
    Element(data, 0x0028, 0x0030, "DS", Decimal(g.spacing_m.y() * 1000) + "\\" + Decimal(g.spacing_m.x() * 1000));
    Element(data, 0x0028, 0x0100, "US", U16(16));
    Element(data, 0x0028, 0x0101, "US", U16(16));
    Element(data, 0x0028, 0x0102, "US", U16(15));
    Element(data, 0x0028, 0x0103, "US", U16(1));
    Element(data, 0x0028, 0x1052, "DS", "0");
    Element(data, 0x0028, 0x1053, "DS", "1");
    std::string pixels;
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) Put16(pixels, static_cast<std::uint16_t>(volume.hu[g.Index(i, j, k)]));
    Element(data, 0x7FE0, 0x0010, "OW", pixels);
    std::string file(128, '\0');
    file += "DICM";
    std::string group_length;
    Put32(group_length, static_cast<std::uint32_t>(meta.size()));
    Element(file, 0x0002, 0x0000, "UL", group_length);
    file += meta + data;
    char name[32];
    std::snprintf(name, sizeof name, "slice_%04d.dcm", k);
    std::ofstream out(directory / name, std::ios::binary);
    out.write(file.data(), static_cast<std::streamsize>(file.size()));
    if (!out) throw PatientFileError((directory / name).string() + ": cannot be written");
  }
}

}  // namespace vesica::app::patient
