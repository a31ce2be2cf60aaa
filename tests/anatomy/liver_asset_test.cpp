// The committed liver surface: size, place, closedness (checked on load) and its labelled regions.
#include <gtest/gtest.h>

#include <algorithm>

#include "anatomy_test_data.h"

namespace vesica::app::anatomy::testing {
namespace {

using physics::kLabelFixed;
using physics::kLabelGallbladderBed;

TEST(LiverAssetTest, ClosedOutwardSurfaceOfAboutAThousandNodes) {
  const physics::TriangleMesh liver = LoadLiver();  // kClosed: manifold, closed, outward
  EXPECT_GE(liver.num_vertices(), 900);
  EXPECT_LE(liver.num_vertices(), 1100);
  // An adult liver holds 1-2 litres.
  EXPECT_GT(physics::EnclosedVolume(liver), 1.0e-3);
  EXPECT_LT(physics::EnclosedVolume(liver), 2.0e-3);
}

TEST(LiverAssetTest, AdultSizedInTheRightUpperQuadrant) {
  const physics::TriangleMesh liver = LoadLiver();
  const auto [lo, hi] = physics::BoundingBox(liver.vertices);
  const Eigen::Vector3d size = hi - lo;
  EXPECT_NEAR(size.x(), 0.20, 0.03);  // right-left
  EXPECT_NEAR(size.y(), 0.15, 0.03);  // posterior-anterior
  EXPECT_NEAR(size.z(), 0.10, 0.03);  // caudal-cranial
  const Eigen::Vector3d centroid = liver.vertices.colwise().mean();
  EXPECT_LT(centroid.x(), -0.02) << "the liver lies on the patient's right (negative x)";
  // Wedge with a thick right lobe: compare cranio-caudal thickness of two slabs across x, the
  // second and fourth fifths of the width (the outermost fifths taper to the rim on both sides).
  auto thickness = [&](double x_min, double x_max) {
    double z_min = 1, z_max = -1;
    for (int i = 0; i < liver.num_vertices(); ++i) {
      if (liver.vertices(i, 0) < x_min || liver.vertices(i, 0) > x_max) continue;
      z_min = std::min(z_min, liver.vertices(i, 2));
      z_max = std::max(z_max, liver.vertices(i, 2));
    }
    return z_max - z_min;
  };
  const double right = thickness(lo.x() + 0.2 * size.x(), lo.x() + 0.4 * size.x());
  const double left = thickness(hi.x() - 0.4 * size.x(), hi.x() - 0.2 * size.x());
  EXPECT_GT(right, 1.2 * left);
}

TEST(LiverAssetTest, FixedRegionIsPosteriorSuperiorWithPlausibleArea) {
  const physics::TriangleMesh liver = LoadLiver();
  ASSERT_EQ(liver.vertex_labels.size(), liver.num_vertices());
  const double area = LabelledArea(liver, kLabelFixed);
  EXPECT_GT(area, 10e-4);   // 10 cm^2
  EXPECT_LT(area, 120e-4);  // 120 cm^2
  const Eigen::Vector3d centre = liver.vertices.colwise().mean();
  const Eigen::Vector3d fixed = LabelledCentroid(liver, kLabelFixed);
  EXPECT_LT(fixed.y(), centre.y() - 0.03) << "bare area is posterior";
  EXPECT_GT(fixed.z(), centre.z()) << "bare area is superior";
}

TEST(LiverAssetTest, GallbladderBedIsOnTheInferiorSurfaceWithPlausibleArea) {
  const physics::TriangleMesh liver = LoadLiver();
  const double area = LabelledArea(liver, kLabelGallbladderBed);
  EXPECT_GT(area, 10e-4);  // 10 cm^2
  EXPECT_LT(area, 80e-4);  // 80 cm^2
  const Eigen::Vector3d centre = liver.vertices.colwise().mean();
  EXPECT_LT(LabelledCentroid(liver, kLabelGallbladderBed).z(), centre.z()) << "bed is on the visceral side";
  for (int i = 0; i < liver.num_vertices(); ++i) {
    EXPECT_NE(liver.vertex_labels[i], kLabelFixed | kLabelGallbladderBed) << "vertex " << i << " in both regions";
  }
}

}  // namespace
}  // namespace vesica::app::anatomy::testing
