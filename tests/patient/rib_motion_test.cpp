// Ribs (seed section 4.3): the inertia matrix's axes (eq. 9), the rib plane, the rotation centre
// on the spine's axis, Table 1's angles at peak and Rodrigues' rotations.
#include "physics/patient/rib_motion.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <vector>

#include "physics/patient/respiration_signal.h"

namespace vesica::physics {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A box of voxels with edge counts 40 x 16 x 3 (spacing 2 mm): symmetric about its centre, so the
// products of inertia vanish in its own frame and its principal axes are its edges, largest spread
// first. Turned by `rotation` and moved to `centre`.
std::vector<Eigen::Vector3d> Plate(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& centre) {
  std::vector<Eigen::Vector3d> points;
  const double h = 0.002;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 16; ++j)
      for (int i = 0; i < 40; ++i)
        points.push_back(centre + rotation * Eigen::Vector3d((i - 19.5) * h, (j - 7.5) * h, (k - 1.0) * h));
  return points;
}

TEST(InertiaMatrixTest, RecoversTheAxesOfASyntheticRib) {
  const Eigen::Matrix3d rotation = (Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(-0.7, Eigen::Vector3d(1, 1, 0).normalized()) *
                                    Eigen::AngleAxisd(0.25, Eigen::Vector3d::UnitX()))
                                       .toRotationMatrix();
  const Eigen::Vector3d centre(0.05, -0.02, 0.1);
  const auto points = Plate(rotation, centre);
  const InertiaAxes axes = ComputeInertiaAxes(points, 8e-9);
  EXPECT_LT((axes.centroid_m - centre).norm(), 1e-12);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(std::abs(axes.principal_axes.col(c).dot(rotation.col(c))), 1.0, 1e-6) << "axis " << c;
  // Eq. 9 is the inertia tensor: its largest eigenvalue belongs to the plate's normal.
  const Eigen::Vector3d n = rotation.col(2);
  const double about_normal = n.dot(axes.inertia_m5 * n);
  for (int c = 0; c < 2; ++c) EXPECT_GT(about_normal, rotation.col(c).dot(axes.inertia_m5 * rotation.col(c)));
  EXPECT_THROW(ComputeInertiaAxes({}, 1.0), std::invalid_argument);
}

TEST(InertiaMatrixTest, SpineAxisIsTheLongAxisPointingCranially) {
  std::vector<Eigen::Vector3d> spine;
  for (int k = 0; k < 100; ++k)
    for (int j = -5; j <= 5; ++j)
      for (int i = -5; i <= 5; ++i)
        if (i * i + j * j <= 25) spine.push_back(Eigen::Vector3d(0.002 * i, -0.05 + 0.002 * j, -0.1 + 0.002 * k));
  const SpineAxis axis = SpineAxisFromVoxels(spine, 8e-9);
  EXPECT_NEAR(axis.direction.z(), 1.0, 1e-12);
  EXPECT_NEAR(axis.point_m.y(), -0.05, 1e-12);
}

// A rib: half an ellipse from the spine round the right side to the front, sloping down by 6 cm.
std::vector<Eigen::Vector3d> RightRib(double z_head) {
  std::vector<Eigen::Vector3d> points;
  for (int s = 0; s <= 300; ++s) {
    const double theta = std::numbers::pi * 0.85 * s / 300.0;
    const Eigen::Vector3d centre(-0.13 * std::sin(theta), -0.045 - 0.09 * std::cos(theta) + 0.04,
                                 z_head - 0.06 * (1.0 - std::cos(theta)) / 2.0);
    for (int d = -1; d <= 1; ++d) points.push_back(centre + Eigen::Vector3d(0, 0, 0.002 * d));
  }
  return points;
}

TEST(RibMotionTest, CentreLiesOnTheSpineAxisAndInTheRibPlane) {
  const SpineAxis spine{Eigen::Vector3d(0.001, -0.05, 0.02), Eigen::Vector3d(0.05, 0.1, 1.0).normalized()};
  const RibModel rib = BuildRibModel(false, 7, RightRib(0.05), 8e-9, spine);
  const Eigen::Vector3d off_axis = (rib.centre_m - spine.point_m).cross(spine.direction);
  EXPECT_LT(off_axis.norm(), 1e-12);
  EXPECT_LT(std::abs(rib.plane_normal.dot(rib.centre_m - rib.inertia.centroid_m)), 1e-12);
  // Both rotation axes lie in the rib plane and are orthogonal.
  EXPECT_NEAR(rib.bucket_axis.dot(rib.plane_normal), 0.0, 1e-12);
  EXPECT_NEAR(rib.pump_axis.dot(rib.plane_normal), 0.0, 1e-12);
  EXPECT_NEAR(rib.bucket_axis.dot(rib.pump_axis), 0.0, 1e-12);
  EXPECT_GT(std::abs(rib.bucket_axis.y()), std::abs(rib.pump_axis.y()));  // bucket handle: front to back
}

TEST(RibMotionTest, AnglesAtPeakAreTableOnes) {
  const double table[][2] = {{14.3, 13.7}, {11.4, 13.3}, {10.7, 10.1}, {9.6, 8.9},
                             {9.4, 6.9},   {7.9, 6.6},   {7.9, 6.2},   {6.0, 6.3}};
  const SpineAxis spine{Eigen::Vector3d(0.0, -0.05, 0.0), Eigen::Vector3d::UnitZ()};
  const double f = 0.27;
  const RespirationSignal signal(RespirationSettings{.frequency_Hz = f});
  const double peak = signal.Unit(1.0 / (4.0 * f));
  for (int n = 2; n <= 9; ++n) {
    const RibModel rib = BuildRibModel(false, n, RightRib(0.2 - 0.023 * (n - 1)), 8e-9, spine);
    const RibPose pose = PoseRib(rib, peak, 1.0);
    EXPECT_NEAR(pose.alpha_rad, table[n - 2][0] * kDeg, 1e-9) << "rib " << n;
    EXPECT_NEAR(pose.beta_rad, table[n - 2][1] * kDeg, 1e-9) << "rib " << n;
    // The rotation is Rodrigues' pump handle after the bucket handle, each by its angle.
    const Eigen::Matrix3d bucket = Rodrigues(rib.bucket_axis, pose.alpha_rad);
    EXPECT_NEAR(std::acos((bucket.trace() - 1.0) / 2.0), pose.alpha_rad, 1e-9);
    EXPECT_LT((bucket * rib.bucket_axis - rib.bucket_axis).norm(), 1e-12);
    EXPECT_LT((pose.rotation - Rodrigues(rib.pump_axis, pose.beta_rad) * bucket).norm(), 1e-12);
    EXPECT_NEAR(pose.rotation.determinant(), 1.0, 1e-12);
    // Inspiration lifts the rib; end tidal leaves it where it was scanned.
    EXPECT_GT(pose.Apply(rib.inertia.centroid_m).z(), rib.inertia.centroid_m.z() + 0.001) << "rib " << n;
    EXPECT_LT((PoseRib(rib, 0.0, 1.0).Apply(rib.inertia.centroid_m) - rib.inertia.centroid_m).norm(), 1e-15);
    // The thoracic scale of seed 6.2 scales both amplitudes.
    EXPECT_NEAR(PoseRib(rib, peak, 0.5).alpha_rad, 0.5 * table[n - 2][0] * kDeg, 1e-9);
  }
}

TEST(RibMotionTest, RibsOutsideTheTable) {
  EXPECT_EQ(Table1Amplitudes(1).alpha_max_deg, 0.0);
  EXPECT_EQ(Table1Amplitudes(1).beta_max_deg, 0.0);
  EXPECT_EQ(Table1Amplitudes(10).alpha_max_deg, 6.0);
  EXPECT_EQ(Table1Amplitudes(10).beta_max_deg, 6.3);
  for (int n : {11, 12}) {
    EXPECT_EQ(Table1Amplitudes(n).alpha_max_deg, 6.0);
    EXPECT_EQ(Table1Amplitudes(n).beta_max_deg, 0.0);
  }
  EXPECT_THROW((void)Table1Amplitudes(13), std::invalid_argument);
}

TEST(RibMotionTest, RibPlaneAlongTheSpineIsRefused) {
  const SpineAxis spine{Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ()};
  const auto vertical = Plate(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitX()).toRotationMatrix(),
                              Eigen::Vector3d(0.05, 0, 0));
  try {
    (void)BuildRibModel(true, 4, vertical, 8e-9, spine);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("left rib 4"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vesica::physics
