// The triangle crossing test against VTK's triangle-triangle intersection
// (vtkIntersectionPolyDataFilter::TriangleTriangleIntersection, a Moller-type test): on random
// pairs without shared vertices both must agree, the pair either way round.
#include <gtest/gtest.h>
#include <vtkIntersectionPolyDataFilter.h>

#include <random>

#include "physics/mesh/triangle_crossing.h"

namespace vesica::physics {
namespace {

TEST(TriangleCrossingVtkTest, AgreesWithVtkOnRandomPairs) {
  std::mt19937 rng(20261127);
  std::uniform_real_distribution<double> coordinate(0.0, 1.0);
  TriangleMesh pair;
  pair.vertices.resize(6, 3);
  pair.triangles.resize(2, 3);
  pair.triangles << 0, 1, 2, 3, 4, 5;
  int crossing = 0, compared = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    for (int i = 0; i < 6; ++i)
      for (int k = 0; k < 3; ++k) pair.vertices(i, k) = coordinate(rng);
    double p[6][3];
    for (int i = 0; i < 6; ++i)
      for (int k = 0; k < 3; ++k) p[i][k] = pair.vertices(i, k);
    int coplanar = 0;
    double a[3], b[3], surface[2];
    const bool vtk = vtkIntersectionPolyDataFilter::TriangleTriangleIntersection(p[0], p[1], p[2], p[3], p[4], p[5],
                                                                                 coplanar, a, b, surface, 0.0) != 0;
    if (coplanar) continue;  // VTK leaves coplanar pairs out; random ones are not
    ++compared;
    crossing += vtk;
    ASSERT_EQ(TrianglesCross(pair, 0, 1), vtk) << "trial " << trial << "\n" << pair.vertices;
    ASSERT_EQ(TrianglesCross(pair, 1, 0), vtk) << "trial " << trial << " (swapped)\n" << pair.vertices;
  }
  EXPECT_EQ(compared, 20000);
  EXPECT_GT(crossing, 2000);  // both outcomes well represented
  EXPECT_LT(crossing, 18000);
}

}  // namespace
}  // namespace vesica::physics
