#pragma once
// The control-point time series vesica-register reads (issue 35; docs/registration.md):
//   frame,time_s,x_m,y_m,z_m,nx,ny,nz,confidence,plane
// one row per tracked point, world frame in metres, (nx, ny, nz) the contour's inward normal
// (any length > 0; normalised on reading), confidence in (0, 1], plane an integer id. Rows of a
// frame are contiguous, frames ascend, a frame's rows share its time and times ascend with frames.
// '#' lines and blank lines are skipped. Every error names the file and the line.

#include <filesystem>
#include <stdexcept>
#include <vector>

#include "physics/mesh/mesh_types.h"
#include "physics/registration/control_point.h"
#include "physics/registration/surface_pairing.h"

namespace vesica::app::registration {

/// Input vesica-register cannot use; what() names the file and line.
class RegisterInputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ControlPointSeries {
  std::vector<physics::ControlFrame> frames;
  std::vector<std::vector<int>> lines;  ///< the file's line of each point, as frames[f].points[p]
};

/// Parses and checks the file. Throws RegisterInputError.
ControlPointSeries ReadControlPointCsv(const std::filesystem::path& file);

/// Every point within max_distance_m of the surface at x_W (any side), else RegisterInputError
/// naming `file` and the point's line.
void CheckPointsNearSurface(const ControlPointSeries& series, const std::filesystem::path& file,
                            const physics::RegistrationSurface& surface, const physics::Vertices& x_W,
                            double max_distance_m);

/// The header line ReadControlPointCsv expects (and vesica-register's sample writer writes).
inline constexpr const char* kControlPointCsvHeader = "frame,time_s,x_m,y_m,z_m,nx,ny,nz,confidence,plane";

}  // namespace vesica::app::registration
