// The committed gallbladder meshes at each resolution: node counts, quality, shape, and their
// placement in the liver's bed.
#include <gtest/gtest.h>

#include <algorithm>

#include "anatomy_test_data.h"
#include "app/anatomy/surface_distance.h"
#include "physics/mesh/mesh_quality.h"
#include "physics/mesh/mesh_topology.h"

namespace vesica::app::anatomy::testing {
namespace {

// Quality every committed resolution must keep (docs/anatomy.md lists the measured values).
constexpr double kMinDihedralDeg = 7.5;
constexpr double kMaxRadiusEdge = 2.0;

class GallbladderAssetTest : public ::testing::TestWithParam<int> {};

TEST_P(GallbladderAssetTest, NodeCountWithinTenPercentOfItsName) {
  const physics::TetrahedralMesh mesh = LoadGallbladder(GetParam());  // validated: no inverted tets
  EXPECT_GE(mesh.num_vertices(), 0.9 * GetParam());
  EXPECT_LE(mesh.num_vertices(), 1.1 * GetParam());
}

TEST_P(GallbladderAssetTest, MeetsTheStatedQualityBounds) {
  const physics::TetQualitySummary q = physics::MeasureTetQuality(LoadGallbladder(GetParam()));
  EXPECT_GE(q.min_dihedral_deg, kMinDihedralDeg);
  EXPECT_LE(q.max_radius_edge, kMaxRadiusEdge);
  EXPECT_LT(q.mean_radius_edge, 1.0);  // the bulk is well shaped (regular tet: 0.612)
}

TEST_P(GallbladderAssetTest, SurfaceFileIsTheClosedBoundaryOfTheVolume) {
  const physics::TetrahedralMesh volume = LoadGallbladder(GetParam());
  const physics::TriangleMesh surface = LoadGallbladderSurface(GetParam());  // kClosed on load
  const physics::TriangleMesh boundary = physics::ExtractBoundary(volume).surface;
  const double tet_volume = physics::TotalVolume(volume);
  EXPECT_EQ(surface.num_vertices(), boundary.num_vertices());
  EXPECT_EQ(surface.num_triangles(), boundary.num_triangles());
  EXPECT_NEAR(physics::EnclosedVolume(boundary), tet_volume, 1e-9 * tet_volume);
  EXPECT_NEAR(physics::EnclosedVolume(surface), tet_volume, 1e-9 * tet_volume);
  // An adult gallbladder holds 30-50 ml.
  EXPECT_GT(tet_volume, 25e-6);
  EXPECT_LT(tet_volume, 50e-6);
}

TEST_P(GallbladderAssetTest, IsAboutEightCentimetresLong) {
  const physics::TriangleMesh surface = LoadGallbladderSurface(GetParam());
  double length = 0;  // the surface's diameter: fundus tip to the end of the duct stub
  for (int i = 0; i < surface.num_vertices(); ++i) {
    for (int j = i + 1; j < surface.num_vertices(); ++j) {
      length = std::max(length, (surface.vertices.row(i) - surface.vertices.row(j)).norm());
    }
  }
  EXPECT_GE(length, 0.07);
  EXPECT_LE(length, 0.09);
}

TEST_P(GallbladderAssetTest, LiesInTheLiverBedWithAGapAndNoInterpenetration) {
  const physics::TriangleMesh liver = LoadLiver();
  const physics::TriangleMesh gallbladder = LoadGallbladderSurface(GetParam());
  double closest = 1;
  for (int i = 0; i < gallbladder.num_vertices(); ++i) {
    const Eigen::Vector3d p = gallbladder.vertices.row(i);
    EXPECT_FALSE(IsInsideClosedSurface(liver, p)) << "gallbladder vertex " << i << " inside the liver";
    closest = std::min(closest, DistanceToSurface(liver, p));
  }
  for (int i = 0; i < liver.num_vertices(); ++i) {
    EXPECT_FALSE(IsInsideClosedSurface(gallbladder, liver.vertices.row(i))) << "liver vertex " << i;
  }
  EXPECT_GE(closest, 0.0015) << "a few millimetres of gap";
  EXPECT_LE(closest, 0.006) << "but it sits in the bed";
  const Eigen::Vector3d bed = LabelledCentroid(liver, physics::kLabelGallbladderBed);
  const Eigen::Vector3d centre = gallbladder.vertices.colwise().mean();
  EXPECT_LT(centre.z(), bed.z()) << "the gallbladder hangs below its bed";
  EXPECT_LT((centre - bed).norm(), 0.03);
}

INSTANTIATE_TEST_SUITE_P(Resolutions, GallbladderAssetTest, ::testing::Values(300, 600, 1000, 1600, 3000),
                         [](const auto& param_info) { return "Nodes" + std::to_string(param_info.param); });

}  // namespace
}  // namespace vesica::app::anatomy::testing
