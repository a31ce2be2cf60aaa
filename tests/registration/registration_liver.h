#pragma once
// The registration tests' organ: the project's liver surface (data/anatomy/liver.vtk) meshed with
// TetGen to the seed's size (1,294 nodes), and the synthetic respiratory truth of issue 35.

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "physics/fem/fem_model.h"
#include "physics/mesh/tetrahedral_mesh.h"
#include "physics/registration/control_point.h"

namespace vesica::test {

/// TetGen switches meshing data/anatomy/liver.vtk to 1,294 nodes and 4,808 tets (quality 2.0 / 5 deg).
inline constexpr const char* kRegistrationLiverTetgenSwitches = "pq2/5a1.1214e-06O2/7YQ";

/// The liver tet mesh (built once per process; TetGen bisects its volume bound to the node count).
const physics::TetrahedralMesh& RegistrationLiverMesh();
/// Its FEM model with the registration's FEM settings (DefaultRegistrationFemSettings).
std::shared_ptr<const physics::FemModel> RegistrationLiverModel();

/// A smooth respiratory field (world frame x left, y anterior, z cranial): at breathing phase
/// s in [0, 1] a translation of 26 mm cranio-caudal, 8 mm anterior-posterior, 2 mm lateral (the
/// top of the seed's ranges), plus a bending of the lobes (cranio-caudal, quadratic in x, 8 mm at
/// the tip, sections turning as in a bent beam) that no rigid motion captures: 35 mm at the tip.
struct RespiratoryField {
  Eigen::Vector3d centre_m;  ///< the liver's centroid at rest
  double tip_x_m = 0.0;      ///< x of the lateral tip (largest |x - centre|)
  Eigen::Vector3d Displacement(const Eigen::Vector3d& X, double phase) const;
};
RespiratoryField MakeRespiratoryField(const physics::TetrahedralMesh& mesh);
/// Breathing phase at time t: sin^2(pi t / 4 s), 0 at end expiration.
double BreathingPhase(double time_s);

/// Contour points of the deformed surface on the coronal plane y = y_c and the sagittal plane
/// x = x_s (tracked in the plane as the seed's slices): `count` points per plane, evenly spread by
/// arc length along the contour, with the in-plane inward normal; noise_m Gaussian noise
/// (seeded) added in the plane. Plane ids 0 coronal, 1 sagittal.
std::vector<physics::ControlPoint> SampleContour(const physics::TetrahedralMesh& mesh, const physics::Vertices& x_W,
                                                 int plane_axis, double plane_value_m, int count, int plane_id,
                                                 double noise_m, unsigned seed);

/// Distances between two configurations of the same mesh's surface: each surface node of `a` to
/// the surface of `b` and each of `b` to `a` (point to triangle).
struct SurfaceError {
  double mean_m = 0.0;
  double max_m = 0.0;
};
SurfaceError SymmetricSurfaceError(const physics::TetrahedralMesh& mesh, const physics::Vertices& a,
                                   const physics::Vertices& b);

}  // namespace vesica::test
