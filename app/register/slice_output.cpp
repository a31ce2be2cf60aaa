#include "app/register/slice_output.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>

#include <algorithm>
#include <stdexcept>

#include "app/patient/patient_files.h"
#include "app/register/control_point_csv.h"

namespace vesica::app::registration {

void ParseSliceSpec(const std::string& spec, physics::SliceAxis& axis, int& index) {
  const auto fail = [&] {
    throw RegisterInputError("--slice '" + spec + "': expected i:INDEX, j:INDEX or k:INDEX (a voxel index)");
  };
  if (spec.size() < 3 || spec[1] != ':') fail();
  if (spec[0] == 'i')
    axis = physics::SliceAxis::kI;
  else if (spec[0] == 'j')
    axis = physics::SliceAxis::kJ;
  else if (spec[0] == 'k')
    axis = physics::SliceAxis::kK;
  else
    fail();
  std::size_t used = 0;
  try {
    index = std::stoi(spec.substr(2), &used);
  } catch (const std::exception&) {
    fail();
  }
  if (used != spec.size() - 2) fail();
}

void WriteSlice(const physics::WarpedSlice& slice, const physics::LabelVolume& ct_grid,
                const std::filesystem::path& stem) {
  vtkNew<vtkImageData> image;
  image->SetDimensions(slice.dims[0], slice.dims[1], 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  auto* pixels = static_cast<unsigned char*>(image->GetScalarPointer());
  constexpr double kLevel_HU = 40.0, kWidth_HU = 400.0;
  for (size_t p = 0; p < slice.values.size(); ++p)
    pixels[p] = static_cast<unsigned char>(
        std::clamp((slice.values[p] - (kLevel_HU - kWidth_HU / 2)) / kWidth_HU * 255.0, 0.0, 255.0));
  vtkNew<vtkPNGWriter> png;
  const std::string png_file = stem.string() + ".png";
  png->SetFileName(png_file.c_str());
  png->SetInputData(image);
  png->Write();
  if (png->GetErrorCode() != 0) throw std::runtime_error(png_file + ": cannot be written");

  patient::PatientVolume volume;
  physics::LabelVolume& grid = volume.labels;
  grid = ct_grid;
  const int normal_axis = static_cast<int>(slice.axis);
  std::array<int, 3> first{0, 0, 0};
  first[static_cast<size_t>(normal_axis)] = slice.index;
  grid.origin_m = ct_grid.Position(first[0], first[1], first[2]);
  grid.dims[static_cast<size_t>(normal_axis)] = 1;
  grid.labels = slice.in_mesh;  // pixel order a fastest is the one-thick grid's i-fastest order
  volume.hu = slice.values;
  patient::WriteNiftiPatient(volume, stem.string() + "_ct.nii.gz", stem.string() + "_labels.nii.gz");
}

}  // namespace vesica::app::registration
