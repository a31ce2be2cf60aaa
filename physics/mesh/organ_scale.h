#pragma once
// A mesh file's size checked before anything is computed on it: organ meshes are authored in
// metres, so a liver 200 units wide was written in millimetres and one at 1e30 is garbage.

#include <string>

#include "physics/mesh/mesh_types.h"

namespace vesica::physics {

/// The largest side of an organ mesh's bounding box that Vesica accepts, metres: 5 mm (a small
/// gallbladder is 3 cm) to 1.5 m (the abdominal wall spans 0.52 m).
inline constexpr double kMinOrganExtent_m = 0.005;
inline constexpr double kMaxOrganExtent_m = 1.5;

/// Throws MeshError "SOURCE: wrong units or scale: ..." naming the extent when the largest side
/// of the bounding box of the finite vertices (#V by 3) is outside [kMinOrganExtent_m,
/// kMaxOrganExtent_m]. Non-finite vertices are left to ValidateTriangleMesh / ValidateTetrahedralMesh,
/// which name them.
void CheckOrganScale(const Vertices& vertices, const std::string& source);

}  // namespace vesica::physics
