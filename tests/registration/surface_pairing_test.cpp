// Pairing (Fig. 2), the best-fit rotation of the warped compliance, and the registration's input
// checks (physics/registration).

#include "physics/registration/surface_pairing.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "physics/mesh/mesh_topology.h"
#include "physics/mesh/primitives.h"
#include "physics/registration/registration_fem_settings.h"
#include "physics/registration/registration_solver.h"

namespace vesica::physics {
namespace {

// Fig. 2(b) at one point: a slab 40 x 40 x 4 mm.
TEST(SurfacePairingTest, TheNormalCheckBindsToTheFaceThatFacesThePoint) {
  const TetrahedralMesh slab = MakeBoxTetMesh(Eigen::Vector3d(0.04, 0.04, 0.004), Eigen::Vector3i(4, 4, 1));
  const RegistrationSurface surface(ExtractBoundary(slab));
  // Tracked as the slab's lower outline (inward normal up), but 5 mm above the mesh's bottom:
  // nearer the upper face (1 mm away) than the lower one (5 mm).
  ControlPoint p{Eigen::Vector3d(0.021, 0.017, 0.005), Eigen::Vector3d::UnitZ(), 1.0, 0};
  const auto nearest = PairControlPoint(surface, slab.vertices, p, {false, 0.0, 0.05});
  ASSERT_TRUE(nearest);
  EXPECT_NEAR(nearest->p_Surface_W.z(), 0.004, 1e-12);
  EXPECT_NEAR(nearest->inward_normal_W.z(), -1.0, 1e-12);
  const auto checked = PairControlPoint(surface, slab.vertices, p, {true, 0.0, 0.05});
  ASSERT_TRUE(checked);
  EXPECT_NEAR(checked->p_Surface_W.z(), 0.0, 1e-12);
  EXPECT_NEAR(checked->inward_normal_W.z(), 1.0, 1e-12);
  EXPECT_NEAR(checked->distance_m, 0.005, 1e-12);
  EXPECT_NEAR(checked->weights.sum(), 1.0, 1e-12);
  // Out of reach: nothing.
  EXPECT_FALSE(PairControlPoint(surface, slab.vertices, p, {true, 0.0, 0.004}));
}

TEST(BestFitRotationTest, RecoversARigidRotationExactly) {
  const TetrahedralMesh box = MakeBoxTetMesh(Eigen::Vector3d(0.1, 0.06, 0.04), Eigen::Vector3i(3, 2, 2));
  const Eigen::Matrix3d r = Eigen::AngleAxisd(2.1, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  Vertices x = box.vertices;
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    x.row(i) = (r * box.vertices.row(i).transpose() + Eigen::Vector3d(0.3, -0.1, 0.2)).transpose();
  const Eigen::VectorXd mass = Eigen::VectorXd::LinSpaced(3 * box.num_vertices(), 1.0, 2.0);
  EXPECT_TRUE(BestFitRotation(box.vertices, x, mass).isApprox(r, 1e-12));
}

TEST(RegistrationSolverTest, RefusesBadSettingsAndPoints) {
  const auto model = std::make_shared<const FemModel>(
      BuildFemModel(MakeBoxTetMesh(Eigen::Vector3d(0.04, 0.04, 0.02), Eigen::Vector3i(2, 2, 1)),
                    DefaultRegistrationFemSettings(), {}));
  RegistrationSettings bad;
  bad.soft_compliance_m_per_N = -1.0;
  EXPECT_THROW(RegistrationSolver(model, bad), std::invalid_argument);
  bad = {};
  bad.min_normal_cosine = 1.5;
  EXPECT_THROW(RegistrationSolver(model, bad), std::invalid_argument);
  bad = {};
  bad.max_pairing_distance_m = 0.0;
  EXPECT_THROW(RegistrationSolver(model, bad), std::invalid_argument);

  RegistrationSolver solver(model, {});
  const ControlPoint good{Eigen::Vector3d(0.02, 0.02, 0.021), -Eigen::Vector3d::UnitZ(), 1.0, 0};
  EXPECT_NO_THROW(solver.Step({good}));
  ControlPoint p = good;
  p.p_W.x() = std::nan("");
  EXPECT_THROW(solver.Step({good, p}), std::invalid_argument);
  p = good;
  p.inward_normal_W.setZero();
  EXPECT_THROW(solver.Step({p}), std::invalid_argument);
  p = good;
  p.confidence = 0.0;
  EXPECT_THROW(solver.Step({p}), std::invalid_argument);
}

}  // namespace
}  // namespace vesica::physics
