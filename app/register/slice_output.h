#pragma once
// vesica-register --warp: the CT slice before and after warping by the registration's field, as
// PNG (abdominal window, width 400 HU at level 40) and as a one-voxel-thick NIfTI volume on the
// CT's own grid (ITK-SNAP and 3D Slicer overlay it on the CT); its label map is 1 where the slice
// lies in the registered mesh.

#include <filesystem>
#include <string>

#include "physics/patient/label_volume.h"
#include "physics/registration/slice_warp.h"

namespace vesica::app::registration {

/// "i:INDEX", "j:INDEX" or "k:INDEX" (a voxel index of the CT's grid). Throws RegisterInputError
/// naming the option.
void ParseSliceSpec(const std::string& spec, physics::SliceAxis& axis, int& index);

/// Writes `slice` as `stem`.png and, on the CT's grid, `stem`_ct.nii.gz and `stem`_labels.nii.gz.
void WriteSlice(const physics::WarpedSlice& slice, const physics::LabelVolume& ct_grid,
                const std::filesystem::path& stem);

}  // namespace vesica::app::registration
