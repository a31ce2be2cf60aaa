// Acceptance of issue 35's registration (physics/registration): the synthetic respiratory truth
// with the seed's numbers against a rigid-only fit, the normal check of Fig. 2(b), and soft
// constraints against an outlier (eq. 6).

#include "physics/registration/registration_solver.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>

#include "physics/mesh/mesh_topology.h"
#include "physics/mesh/primitives.h"
#include "physics/registration/registration_fem_settings.h"
#include "physics/registration/rigid_fit.h"
#include "tests/registration/registration_liver.h"

namespace vesica::physics {
namespace {

using test::RegistrationLiverMesh;
using test::RegistrationLiverModel;

constexpr int kFrames = 46;  // the seed's sequence
constexpr double kFramePeriod_s = 0.4175;
constexpr int kCoronalPoints = 18;
constexpr int kSagittalPoints = 12;
constexpr double kNoise_m = 0.5e-3;
constexpr int kStepsPerFrame = 8;
constexpr double kDefaultSoftCompliance_m_per_N = 0.01;

Vertices Deformed(const test::RespiratoryField& field, const TetrahedralMesh& mesh, double phase) {
  Vertices x = mesh.vertices;
  for (Eigen::Index i = 0; i < x.rows(); ++i) x.row(i) += field.Displacement(x.row(i).transpose(), phase).transpose();
  return x;
}

std::vector<ControlPoint> FramePoints(const TetrahedralMesh& mesh, const Vertices& truth, const Eigen::Vector3d& centre,
                                      int frame, double noise_m) {
  std::vector<ControlPoint> points =
      test::SampleContour(mesh, truth, 1, centre.y(), kCoronalPoints, 0, noise_m, 1000u + static_cast<unsigned>(frame));
  const std::vector<ControlPoint> sagittal = test::SampleContour(mesh, truth, 0, centre.x(), kSagittalPoints, 1,
                                                                 noise_m, 2000u + static_cast<unsigned>(frame));
  points.insert(points.end(), sagittal.begin(), sagittal.end());
  return points;
}

TEST(RegistrationSolverTest, SyntheticRespirationIsRegisteredWhereARigidFitIsNot) {
  const TetrahedralMesh& mesh = RegistrationLiverMesh();
  ASSERT_NEAR(mesh.num_vertices(), 1294, 15);
  const test::RespiratoryField field = test::MakeRespiratoryField(mesh);
  RegistrationSolver solver(RegistrationLiverModel(), {});
  const RegistrationSurface surface(ExtractBoundary(mesh));
  Eigen::Isometry3d rigid = Eigen::Isometry3d::Identity();
  double registered_mean = 0.0, registered_max = 0.0, rigid_mean = 0.0, rigid_max = 0.0, peak_displacement = 0.0;
  for (int frame = 0; frame < kFrames; ++frame) {
    const double phase = test::BreathingPhase(frame * kFramePeriod_s);
    const Vertices truth = Deformed(field, mesh, phase);
    peak_displacement = std::max(peak_displacement, (truth - mesh.vertices).rowwise().norm().maxCoeff());
    const std::vector<ControlPoint> points = FramePoints(mesh, truth, field.centre_m, frame, kNoise_m);
    ASSERT_EQ(points.size(), static_cast<size_t>(kCoronalPoints + kSagittalPoints)) << "frame " << frame;
    for (int step = 0; step < kStepsPerFrame; ++step) {
      const RegistrationStepReport report = solver.Step(points);
      ASSERT_TRUE(report.fem.accepted) << report.fem.rejection_reason;
      ASSERT_EQ(report.paired_points, static_cast<int>(points.size()));
    }
    rigid = FitRigid(surface, mesh.vertices, points, rigid);
    if (frame % 3 != 0) continue;  // the error every third frame (the surface distances are costly)
    const test::SurfaceError registered = test::SymmetricSurfaceError(mesh, solver.CurrentPositions(), truth);
    const test::SurfaceError rigid_error =
        test::SymmetricSurfaceError(mesh, TransformVertices(mesh.vertices, rigid), truth);
    registered_mean = std::max(registered_mean, registered.mean_m);
    registered_max = std::max(registered_max, registered.max_m);
    rigid_mean = std::max(rigid_mean, rigid_error.mean_m);
    rigid_max = std::max(rigid_max, rigid_error.max_m);
    std::printf("frame %2d phase %.2f: registered mean %.2f max %.2f mm; rigid mean %.2f max %.2f mm\n", frame, phase,
                1e3 * registered.mean_m, 1e3 * registered.max_m, 1e3 * rigid_error.mean_m, 1e3 * rigid_error.max_m);
  }
  std::printf("worst frame: registered mean %.2f max %.2f mm; rigid mean %.2f max %.2f mm; truth up to %.1f mm\n",
              1e3 * registered_mean, 1e3 * registered_max, 1e3 * rigid_mean, 1e3 * rigid_max, 1e3 * peak_displacement);
  EXPECT_GT(peak_displacement, 0.030);  // the seed's "up to 35 mm"
  EXPECT_LT(peak_displacement, 0.036);
  EXPECT_LT(registered_mean, 1e-3);
  EXPECT_LT(registered_max, 3e-3);
  EXPECT_TRUE(rigid_mean >= 1e-3 || rigid_max >= 3e-3) << "a rigid fit should not capture the bending";
}

// Fig. 2(b): a slab 10 mm thick whose outline was tracked 12 mm above where the mesh starts, more
// than its thickness. By distance alone the points under the slab bind to its upper face, as do
// those above it: the constraints pull one face both ways, cannot be met, and the slab is torn
// (re-pairing every step does not recover it). With the normal check the points below bind to
// the lower face and the slab moves up as a whole. (At 7 mm, the ICP re-pairing recovers after
// ~10 steps even without the check: the test needs the seed's "all on one side".)
double RegisterShiftedSlab(bool check_normals, int* wrong_side_pairs) {
  const TetrahedralMesh slab = MakeBoxTetMesh(Eigen::Vector3d(0.080, 0.080, 0.010), Eigen::Vector3i(10, 10, 2));
  const auto model = std::make_shared<const FemModel>(BuildFemModel(slab, DefaultRegistrationFemSettings("slab"), {}));
  const Eigen::Vector3d shift(0.0, 0.0, 0.012);
  Vertices truth = slab.vertices;
  truth.rowwise() += shift.transpose();
  const Eigen::Vector3d centre = truth.colwise().mean().transpose();
  std::vector<ControlPoint> points = test::SampleContour(slab, truth, 1, centre.y(), kCoronalPoints, 0, 0.0, 1);
  const std::vector<ControlPoint> sagittal =
      test::SampleContour(slab, truth, 0, centre.x(), kSagittalPoints, 1, 0.0, 2);
  points.insert(points.end(), sagittal.begin(), sagittal.end());
  RegistrationSettings settings;
  settings.check_normals = check_normals;
  RegistrationSolver solver(model, settings);
  for (int step = 0; step < 40; ++step) {
    const RegistrationStepReport report = solver.Step(points);
    EXPECT_TRUE(report.fem.accepted) << report.fem.rejection_reason;
    if (step == 0) {
      *wrong_side_pairs = 0;
      for (size_t i = 0; i < solver.last_pairings().size(); ++i)
        if (solver.last_pairings()[i].inward_normal_W.dot(points[i].inward_normal_W) < 0.0) ++*wrong_side_pairs;
    }
  }
  const test::SurfaceError error = test::SymmetricSurfaceError(slab, solver.CurrentPositions(), truth);
  std::printf(
      "normal check %s: %d of %zu pairs on the wrong side at the first step; surface error mean %.2f max %.2f mm\n",
      check_normals ? "on" : "off", *wrong_side_pairs, points.size(), 1e3 * error.mean_m, 1e3 * error.max_m);
  return error.mean_m;
}

TEST(RegistrationSolverTest, NormalCheckPreventsBindingToTheWrongSide) {
  int wrong_without = 0, wrong_with = 0;
  const double error_without = RegisterShiftedSlab(false, &wrong_without);
  const double error_with = RegisterShiftedSlab(true, &wrong_with);
  EXPECT_GT(wrong_without, 0);
  EXPECT_EQ(wrong_with, 0);
  EXPECT_GT(error_without, 3e-3);
  EXPECT_LT(error_with, 1e-3);
}

// The seed's liver "re-orients as it settles": the outline tracked on a liver turned 90 degrees
// about the anterior-posterior axis and moved 10 mm, the mesh starting at rest. Every step stays
// accepted and the body's best-fit rotation, which turns the compliance (R C0 R^T), finds the turn.
// With R = I (the rest compliance unturned) the same run ends 13.8 mm off on average (measured;
// at 45-60 degrees both converge): the warped compliance is what keeps W right.
TEST(RegistrationSolverTest, ALargeRotationIsFollowedStably) {
  const TetrahedralMesh& mesh = RegistrationLiverMesh();
  const Eigen::Vector3d centre = mesh.vertices.colwise().mean().transpose();
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(90.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  Vertices truth = mesh.vertices;
  for (Eigen::Index i = 0; i < truth.rows(); ++i)
    truth.row(i) =
        (centre + turn * (mesh.vertices.row(i).transpose() - centre) + Eigen::Vector3d(0.0, 0.0, -0.010)).transpose();
  const std::vector<ControlPoint> points = FramePoints(mesh, truth, centre + Eigen::Vector3d(0.0, 0.0, -0.010), 0, 0.0);
  RegistrationSolver solver(RegistrationLiverModel(), {});
  for (int step = 0; step < 60; ++step) {
    const RegistrationStepReport report = solver.Step(points);
    ASSERT_TRUE(report.fem.accepted) << "step " << step << ": " << report.fem.rejection_reason;
  }
  const Eigen::AngleAxisd found(solver.last_rotation());
  const test::SurfaceError error = test::SymmetricSurfaceError(mesh, solver.CurrentPositions(), truth);
  std::printf("90 deg turn: registered rotation %.1f deg, surface error mean %.2f max %.2f mm\n",
              found.angle() * 180.0 / M_PI, 1e3 * error.mean_m, 1e3 * error.max_m);
  EXPECT_NEAR(found.angle() * 180.0 / M_PI, 90.0, 2.0);
  EXPECT_LT(error.mean_m, 1e-3);
}

// Eq. 6: one control point tracked 10 mm off the surface (outward), its confidence low. Hard
// constraints tear the surface out to it; soft ones let the outline give instead.
double OutlierPull(double soft_compliance_m_per_N) {
  const TetrahedralMesh& mesh = RegistrationLiverMesh();
  const test::RespiratoryField field = test::MakeRespiratoryField(mesh);
  std::vector<ControlPoint> points = FramePoints(mesh, mesh.vertices, field.centre_m, 0, 0.0);
  ControlPoint& outlier = points[4];
  outlier.p_W -= 0.010 * outlier.inward_normal_W.normalized();
  outlier.confidence = 0.05;
  RegistrationSettings settings;
  settings.soft_compliance_m_per_N = soft_compliance_m_per_N;
  RegistrationSolver solver(RegistrationLiverModel(), settings);
  for (int step = 0; step < 30; ++step) {
    const RegistrationStepReport report = solver.Step(points);
    EXPECT_TRUE(report.fem.accepted) << report.fem.rejection_reason;
  }
  const double moved = solver.Displacement().rowwise().norm().maxCoeff();
  std::printf("soft compliance %.3g m/N: the surface moved up to %.2f mm\n", soft_compliance_m_per_N, 1e3 * moved);
  return moved;
}

TEST(RegistrationSolverTest, SoftConstraintsKeepAnOutlierFromTearingTheSurface) {
  EXPECT_GT(OutlierPull(0.0), 5e-3);
  EXPECT_LT(OutlierPull(kDefaultSoftCompliance_m_per_N), 2e-3);
}

}  // namespace
}  // namespace vesica::physics
