// The organs' serosa texture: deterministic, keeps the tissue's hue (it only multiplies), has
// reddish capillaries, tiles without a seam, and sticks to the tissue as the surface deforms.

#include <gtest/gtest.h>

#include <vtkActor.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkTexture.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "app/render/organ_surface.h"
#include "app/render/tissue_texture.h"
#include "physics/mesh/primitives.h"

namespace vesica::app {
namespace {

constexpr int kSize = 256;

double Pixel(const std::vector<std::uint8_t>& img, int x, int y, int c) {
  return img[3 * (static_cast<std::size_t>(y) * kSize + x) + c] / 255.0;
}

TEST(TissueTextureTest, IsDeterministicAndDependsOnTheSeed) {
  EXPECT_EQ(TissueTexturePixels(kSize, 7), TissueTexturePixels(kSize, 7));
  EXPECT_NE(TissueTexturePixels(kSize, 7), TissueTexturePixels(kSize, 8));
  EXPECT_EQ(TissueTexturePixels(kSize, 7).size(), 3u * kSize * kSize);
}

TEST(TissueTextureTest, DarkensOnlySlightlyOnAverageWithReddishCapillaries) {
  const auto img = TissueTexturePixels(kSize, 7);
  double mean[3] = {0, 0, 0};
  int vessel_pixels = 0, reddish = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      for (int c = 0; c < 3; ++c) mean[c] += Pixel(img, x, y, c) / (kSize * kSize);
      if (Pixel(img, x, y, 1) < 0.8) {
        ++vessel_pixels;
        reddish += Pixel(img, x, y, 0) > Pixel(img, x, y, 1) + 0.05 ? 1 : 0;
      }
    }
  // A multiplier close to 1 keeps the liver red and the gallbladder green (the image checks).
  for (double m : mean) {
    EXPECT_GT(m, 0.85);
    EXPECT_LE(m, 1.0);
  }
  const double fraction = static_cast<double>(vessel_pixels) / (kSize * kSize);
  EXPECT_GT(fraction, 0.02);  // capillaries are there...
  EXPECT_LT(fraction, 0.25);  // ...but thin
  EXPECT_EQ(reddish, vessel_pixels);
}

TEST(TissueTextureTest, TilesWithoutASeam) {
  // Repeated across the organ, the last column meets the first and the last row the first: the
  // jump there must look like any jump between neighbouring pixels inside.
  const auto img = TissueTexturePixels(kSize, 7);
  auto column_jump = [&](int x0, int x1) {
    double sum = 0;
    for (int y = 0; y < kSize; ++y) sum += std::abs(Pixel(img, x0, y, 1) - Pixel(img, x1, y, 1));
    return sum / kSize;
  };
  auto row_jump = [&](int y0, int y1) {
    double sum = 0;
    for (int x = 0; x < kSize; ++x) sum += std::abs(Pixel(img, x, y0, 1) - Pixel(img, x, y1, 1));
    return sum / kSize;
  };
  double interior_columns = 0, interior_rows = 0;
  for (int i = 0; i + 1 < kSize; ++i) {
    interior_columns += column_jump(i, i + 1) / (kSize - 1);
    interior_rows += row_jump(i, i + 1) / (kSize - 1);
  }
  EXPECT_LT(column_jump(kSize - 1, 0), 1.6 * interior_columns);
  EXPECT_LT(row_jump(kSize - 1, 0), 1.6 * interior_rows);
}

TEST(TissueTextureTest, RejectsASizeOutOfRange) {
  EXPECT_THROW(TissueTexturePixels(8, 1), std::invalid_argument);
  EXPECT_THROW(TissueTexturePixels(5000, 1), std::invalid_argument);
}

TEST(TissueTextureTest, OrganTextureCoordinatesAreTheRestShapeBoxMappedAndStickToTheTissue) {
  const physics::TriangleMesh sphere = physics::MakeIcosphere(0.05, 2);
  const double rgb[3] = {0.6, 0.2, 0.2};
  const double tile = 0.03;
  auto texture = MakeTissueTexture(64, 3);
  OrganSurface organ(sphere, rgb, 0.1, 1.0, texture, tile);
  EXPECT_EQ(organ.actor()->GetTexture(), texture.Get());
  vtkDataArray* tcoords = organ.poly_data()->GetPointData()->GetTCoords();
  ASSERT_NE(tcoords, nullptr);
  ASSERT_EQ(tcoords->GetNumberOfTuples(), 3 * sphere.num_triangles());
  ASSERT_EQ(tcoords->GetNumberOfComponents(), 2);

  auto check = [&] {
    for (int f = 0; f < sphere.num_triangles(); ++f) {
      const Eigen::Vector3d a = sphere.vertices.row(sphere.triangles(f, 0)).transpose();
      const Eigen::Vector3d n =
          (sphere.vertices.row(sphere.triangles(f, 1)).transpose() - a)
              .cross(sphere.vertices.row(sphere.triangles(f, 2)).transpose() - a);
      // Projected along the axis of the largest normal component: (u, v) * tile are the rest
      // coordinates on the other two axes, so a triangle's texture is undistorted up to 55 deg.
      int axis = 0;
      n.cwiseAbs().maxCoeff(&axis);
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d p = sphere.vertices.row(sphere.triangles(f, k)).transpose();
        const double* uv = tcoords->GetTuple2(3 * f + k);
        EXPECT_NEAR(uv[0] * tile, p((axis + 1) % 3), 1e-7) << "triangle " << f;
        EXPECT_NEAR(uv[1] * tile, p((axis + 2) % 3), 1e-7) << "triangle " << f;
      }
    }
  };
  check();
  // Deform the surface (stretch and shift): positions move, the texture coordinates do not.
  physics::Vertices deformed = sphere.vertices;
  deformed.col(0) *= 1.4;
  deformed.col(2).array() += 0.02;
  organ.SetVertices(deformed);
  double moved[3];
  organ.poly_data()->GetPoints()->GetPoint(0, moved);
  EXPECT_NEAR(moved[2], deformed(sphere.triangles(0, 0), 2), 1e-12);
  check();
}

TEST(TissueTextureTest, UntexturedOrganHasNoTextureCoordinates) {
  const physics::TriangleMesh sphere = physics::MakeIcosphere(0.05, 1);
  const double rgb[3] = {0.6, 0.2, 0.2};
  OrganSurface organ(sphere, rgb, 0.1, 1.0);
  EXPECT_EQ(organ.poly_data()->GetPointData()->GetTCoords(), nullptr);
  EXPECT_EQ(organ.actor()->GetTexture(), nullptr);
}

}  // namespace
}  // namespace vesica::app
