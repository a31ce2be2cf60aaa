// Self-intersection: crossing triangle pairs are found and named; valid surfaces, flat regions
// included (coplanar neighbours sharing a vertex), give none.
#include "physics/mesh/self_intersection.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "physics/mesh/mesh_topology.h"
#include "physics/mesh/mesh_validation.h"
#include "physics/mesh/primitives.h"
#include "physics/mesh/triangle_crossing.h"

namespace vesica::physics {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using Pairs = std::vector<std::pair<int, int>>;

/// The outward surface of the tetrahedron (a, a + s x, a + s y, a + s z).
TriangleMesh TetSurface(const Eigen::Vector3d& a, double s) {
  TriangleMesh m;
  m.vertices.resize(4, 3);
  m.vertices.row(0) = a.transpose();
  m.vertices.row(1) = (a + s * Eigen::Vector3d::UnitX()).transpose();
  m.vertices.row(2) = (a + s * Eigen::Vector3d::UnitY()).transpose();
  m.vertices.row(3) = (a + s * Eigen::Vector3d::UnitZ()).transpose();
  m.triangles.resize(4, 3);
  m.triangles << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  return m;
}

/// Both surfaces in one mesh, b's vertices and triangles after a's.
TriangleMesh Union(const TriangleMesh& a, const TriangleMesh& b) {
  TriangleMesh m;
  m.vertices.resize(a.num_vertices() + b.num_vertices(), 3);
  m.vertices << a.vertices, b.vertices;
  m.triangles.resize(a.num_triangles() + b.num_triangles(), 3);
  m.triangles << a.triangles, (b.triangles.array() + a.num_vertices()).matrix();
  return m;
}

/// Two triangles from explicit corners (one mesh, six rows of vertices unless indices share).
TriangleMesh Pair(const Vertices& v, const Eigen::Vector3i& f, const Eigen::Vector3i& g) {
  TriangleMesh m;
  m.vertices = v;
  m.triangles.resize(2, 3);
  m.triangles.row(0) = f.transpose();
  m.triangles.row(1) = g.transpose();
  return m;
}

TEST(SelfIntersectionTest, ValidSurfacesHaveNone) {
  EXPECT_TRUE(SelfIntersections(MakeIcosphere(0.05, 3)).empty());
  // Flat faces: many coplanar triangles sharing one vertex or an edge, none overlapping.
  EXPECT_TRUE(SelfIntersections(ExtractBoundary(MakeBoxTetMesh({0.1, 0.05, 0.02}, {5, 4, 3})).surface).empty());
  EXPECT_TRUE(SelfIntersections(Union(TetSurface({0, 0, 0}, 0.01), TetSurface({0.02, 0, 0}, 0.01))).empty());
}

TEST(SelfIntersectionTest, InterpenetratingTetrahedraGiveTheirCrossingPairs) {
  // The second tetrahedron's corner (0.002, 0.002, 0.002) lies inside the first: its three faces
  // at that corner pass through the first's slanted face (triangle 3) only.
  const TriangleMesh m = Union(TetSurface({0, 0, 0}, 0.01), TetSurface({0.002, 0.002, 0.002}, 0.01));
  EXPECT_THAT(SelfIntersections(m), ElementsAre(std::pair(3, 4), std::pair(3, 5), std::pair(3, 6)));
  // The same shapes apart do not cross.
  EXPECT_TRUE(SelfIntersections(Union(TetSurface({0, 0, 0}, 0.01), TetSurface({0.011, 0, 0}, 0.01))).empty());
}

TEST(SelfIntersectionTest, PairWithoutSharedVertex) {
  Vertices v(6, 3);
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0,          // in z = 0
      0.2, 0.2, -1, 0.2, 0.2, 1, 2, 2, 0;  // its edge (3, 4) passes through the first at (0.2, 0.2, 0)
  EXPECT_TRUE(TrianglesCross(Pair(v, {0, 1, 2}, {3, 4, 5}), 0, 1));
  v.row(3) << 0.2, 0.2, 0.5;  // above the plane now: no crossing
  v.row(5) << 2, 2, 0.5;
  EXPECT_FALSE(TrianglesCross(Pair(v, {0, 1, 2}, {3, 4, 5}), 0, 1));
  // Coplanar: overlapping, apart, and one inside the other.
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.2, 0.2, 0, 1, 0.2, 0, 0.2, 1, 0;
  EXPECT_TRUE(TrianglesCross(Pair(v, {0, 1, 2}, {3, 4, 5}), 0, 1));
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0, 1, 2, 0;
  EXPECT_FALSE(TrianglesCross(Pair(v, {0, 1, 2}, {3, 4, 5}), 0, 1));
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.1, 0.1, 0, 0.3, 0.1, 0, 0.1, 0.3, 0;
  EXPECT_TRUE(TrianglesCross(Pair(v, {0, 1, 2}, {3, 4, 5}), 0, 1));
  // The same triangle at other indices.
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0;
  EXPECT_TRUE(TrianglesCross(Pair(v, {0, 1, 2}, {3, 5, 4}), 0, 1));
  // Touching at a point without passing through is not a crossing.
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.2, 0.2, 0, 0.2, 0.2, 1, 1, 1, 1;
  EXPECT_FALSE(TrianglesCross(Pair(v, {0, 1, 2}, {3, 4, 5}), 0, 1));
}

TEST(SelfIntersectionTest, PairSharingAVertex) {
  Vertices v(5, 3);
  // Fan neighbours in one plane: they meet at vertex 0 only.
  v << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, -1, 1, 0;
  EXPECT_FALSE(TrianglesCross(Pair(v, {0, 1, 2}, {0, 3, 4}), 0, 1));
  // In one plane with overlapping wedges at vertex 0.
  v << 0, 0, 0, 1, 0, 0, 1, 1, 0, 1, 0.5, 0, 0, 1, 0;
  EXPECT_TRUE(TrianglesCross(Pair(v, {0, 1, 2}, {0, 3, 4}), 0, 1));
  // The same wedge, other far corners.
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0, 0, 2, 0;
  EXPECT_TRUE(TrianglesCross(Pair(v, {0, 1, 2}, {0, 3, 4}), 0, 1));
  // Across the plane: the second's far edge (3, 4) passes through the first.
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.4, 0.4, -1, 0.4, 0.4, 1;
  EXPECT_TRUE(TrianglesCross(Pair(v, {0, 1, 2}, {0, 3, 4}), 0, 1));
  // A sharp but open fold about the shared vertex.
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 0, 0.1, 0, 1, 0.1;
  EXPECT_FALSE(TrianglesCross(Pair(v, {0, 1, 2}, {0, 3, 4}), 0, 1));
}

TEST(SelfIntersectionTest, PairSharingAnEdgeCrossesOnlyWhenFolded) {
  Vertices v(4, 3);
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.5, -0.5, 0;  // flat continuation across edge (0, 1)
  EXPECT_FALSE(TrianglesCross(Pair(v, {0, 1, 2}, {1, 0, 3}), 0, 1));
  v.row(3) << 0.5, 0.5, 0;  // folded back onto the first
  EXPECT_TRUE(TrianglesCross(Pair(v, {0, 1, 2}, {1, 0, 3}), 0, 1));
  v.row(3) << 0.5, 0.5, 0.01;  // a sharp edge, not folded
  EXPECT_FALSE(TrianglesCross(Pair(v, {0, 1, 2}, {1, 0, 3}), 0, 1));
}

TEST(SelfIntersectionTest, ClosedSurfaceThatIntersectsItselfIsRefusedNamingThePairs) {
  const TriangleMesh m = Union(TetSurface({0, 0, 0}, 0.01), TetSurface({0.002, 0.002, 0.002}, 0.01));
  try {
    ValidateTriangleMesh(m, "liver.obj", SurfaceRequirement::kClosed);
    FAIL() << "no error";
  } catch (const MeshError& e) {
    EXPECT_EQ(std::string(e.what()),
              "liver.obj: mesh: intersects itself: 3 pairs of triangles cross: triangle 3 and triangle 4; "
              "triangle 3 and triangle 5; triangle 3 and triangle 6");
  }
  EXPECT_NO_THROW(ValidateTriangleMesh(m, "liver.obj", SurfaceRequirement::kAny));
}

TEST(SelfIntersectionTest, VertexPushedThroughAClosedSurfaceIsFound) {
  // An icosphere with one vertex pushed through and out of the far side: its fan crosses the sphere.
  TriangleMesh m = MakeIcosphere(0.05, 2);
  m.vertices.row(0) *= -1.3;
  const auto pairs = SelfIntersections(m);
  ASSERT_FALSE(pairs.empty());
  for (const auto& [f, g] : pairs) {
    const bool f_uses_0 = (m.triangles.row(f).array() == 0).any(), g_uses_0 = (m.triangles.row(g).array() == 0).any();
    EXPECT_TRUE(f_uses_0 || g_uses_0) << f << ", " << g;
  }
}

}  // namespace
}  // namespace vesica::physics
