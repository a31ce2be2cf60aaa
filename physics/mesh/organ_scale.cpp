#include "physics/mesh/organ_scale.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "physics/mesh/mesh_validation.h"

namespace vesica::physics {

void CheckOrganScale(const Vertices& vertices, const std::string& source) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  bool any_finite = false;
  for (Eigen::Index i = 0; i < vertices.rows(); ++i) {
    if (!vertices.row(i).allFinite()) continue;
    lo = lo.cwiseMin(vertices.row(i).transpose());
    hi = hi.cwiseMax(vertices.row(i).transpose());
    any_finite = true;
  }
  if (!any_finite) return;
  const Eigen::Vector3d extent = hi - lo;  // may overflow to inf for vertices near +-1e308
  const double largest = extent.maxCoeff();
  if (largest >= kMinOrganExtent_m && largest <= kMaxOrganExtent_m) return;
  std::ostringstream os;
  os.precision(3);
  os << source << ": wrong units or scale: the mesh spans " << extent.x() << " x " << extent.y() << " x " << extent.z()
     << " m (from (" << lo.x() << ", " << lo.y() << ", " << lo.z() << ") to (" << hi.x() << ", " << hi.y() << ", "
     << hi.z() << ")); an organ mesh spans " << kMinOrganExtent_m << " to " << kMaxOrganExtent_m << " m, in metres";
  if (largest > kMaxOrganExtent_m && largest <= 1000 * kMaxOrganExtent_m)
    os << " (is the file in millimetres or centimetres?)";
  throw MeshError(os.str());
}

}  // namespace vesica::physics
