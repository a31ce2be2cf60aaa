// The CT guidance images' geometry (app/biopsy/ct_slice): pixels and world points round-trip, the
// oblique plane holds the needle, the window maps HU to grey, and at end tidal a slice reads the
// CT's own voxels.

#include "app/biopsy/ct_slice.h"

#include <gtest/gtest.h>

#include "app/biopsy/biopsy_patient.h"

namespace vesica::app::biopsy {
namespace {

TEST(CtSliceTest, PixelCentresProjectBackOntoThemselves) {
  const SlicePlane axial = AxialSliceThrough(Eigen::Vector3d(-0.07, 0.03, -0.04), 0.002, 64);
  for (int c : {0, 17, 63})
    for (int r : {0, 40, 63}) {
      const SlicePoint p = ProjectOntoSlice(axial, PixelCentre(axial, c, r));
      EXPECT_NEAR(p.pixel.x(), c + 0.5, 1e-9);
      EXPECT_NEAR(p.pixel.y(), r + 0.5, 1e-9);
      EXPECT_NEAR(p.off_plane_m, 0.0, 1e-15);
    }
  // Radiological convention: the patient's left to the right of the image, anterior at the top.
  EXPECT_GT(ProjectOntoSlice(axial, Eigen::Vector3d(0.0, 0.03, -0.04)).pixel.x(), 32);
  EXPECT_LT(ProjectOntoSlice(axial, Eigen::Vector3d(-0.07, 0.06, -0.04)).pixel.y(), 32);
  EXPECT_NEAR(ProjectOntoSlice(axial, Eigen::Vector3d(-0.07, 0.03, -0.035)).off_plane_m, -0.005, 1e-15);
}

TEST(CtSliceTest, ObliquePlaneHoldsTheWholeNeedleWhateverItsDirection) {
  for (const Eigen::Vector3d& d : {Eigen::Vector3d(0, -1, 0), Eigen::Vector3d(1, -1, 0.3), Eigen::Vector3d(0, 0, 1),
                                   Eigen::Vector3d(0.2, -0.1, -1)}) {
    const physics::NeedlePose pose{Eigen::Vector3d(-0.07, 0.05, -0.04), d};
    const SlicePlane plane = ObliqueSliceAlong(pose);
    EXPECT_NEAR(plane.column_W.norm(), 1.0, 1e-12);
    EXPECT_NEAR(plane.row_W.norm(), 1.0, 1e-12);
    EXPECT_NEAR(plane.column_W.dot(plane.row_W), 0.0, 1e-12);
    for (double s : {-0.15, -0.05, 0.0, 0.08}) {
      const SlicePoint p = ProjectOntoSlice(plane, pose.tip_m + s * d.normalized());
      EXPECT_NEAR(p.off_plane_m, 0.0, 1e-12) << d.transpose();
      EXPECT_NEAR(p.pixel.y(), plane.rows / 2.0, 1e-9);  // the needle runs along the middle row
    }
  }
}

TEST(CtSliceTest, AbdominalWindowMapsItsEndsToBlackAndWhite) {
  EXPECT_EQ(WindowHu(-160.0f), 0);
  EXPECT_EQ(WindowHu(-1000.0f), 0);
  EXPECT_EQ(WindowHu(240.0f), 255);
  EXPECT_EQ(WindowHu(700.0f), 255);
  EXPECT_EQ(WindowHu(40.0f), 128);  // 127.5 rounds up
}

TEST(CtSliceTest, AtEndTidalAnAxialSliceOnVoxelCentresReadsTheCtVoxels) {
  const auto patient = LoadCommittedBiopsyPatient(std::filesystem::path(VESICA_DATA_DIR) / "patients");
  physics::BreathingPatient breathing(patient->model);
  breathing.Update(0.0);  // M(0) = 0: end tidal, the scanned position
  physics::DeformedCt ct(patient->ct);
  ct.SetPatient(breathing.snapshot());
  ct.SetBlend(1.0);
  const physics::LabelVolume& grid = patient->volume.labels;
  // A plane through voxel centres, one pixel a voxel, over the liver and the ribs.
  const int i0 = 20, j0 = 40, k0 = 80, n = 24;
  const auto centre = [&](int i, int j, int k) { return grid.Position(i, j, k); };
  SlicePlane plane;
  plane.pixel_m = grid.spacing_m.x();
  plane.columns = plane.rows = n;
  plane.column_W = (centre(i0 + 1, j0, k0) - centre(i0, j0, k0)).normalized();
  plane.row_W = (centre(i0, j0 + 1, k0) - centre(i0, j0, k0)).normalized();
  plane.centre_W = centre(i0, j0, k0) + (n / 2.0 - 0.5) * plane.pixel_m * (plane.column_W + plane.row_W);
  const std::vector<float> hu = SampleSlice(ct, plane);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c)
      EXPECT_NEAR(hu[r * n + c], patient->volume.hu[grid.Index(i0 + c, j0 + r, k0)], 1e-3) << c << ", " << r;
}

}  // namespace
}  // namespace vesica::app::biopsy
