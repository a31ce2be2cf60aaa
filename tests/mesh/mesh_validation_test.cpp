#include "physics/mesh/mesh_validation.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

#include "physics/mesh/mesh_topology.h"
#include "physics/mesh/primitives.h"

namespace vesica::physics {
namespace {

using ::testing::HasSubstr;

std::string SurfaceError(const TriangleMesh& m, SurfaceRequirement r = SurfaceRequirement::kClosed) {
  try {
    ValidateTriangleMesh(m, "liver.obj", r);
  } catch (const MeshError& e) {
    return e.what();
  }
  return "no error";
}

std::string VolumeError(const TetrahedralMesh& m) {
  try {
    ValidateTetrahedralMesh(m, "gallbladder.vtu");
  } catch (const MeshError& e) {
    return e.what();
  }
  return "no error";
}

TEST(MeshValidationTest, GoodMeshesPass) {
  EXPECT_EQ(SurfaceError(MakeIcosphere(0.05, 2)), "no error");
  EXPECT_EQ(VolumeError(MakeBoxTetMesh({1, 1, 1}, {2, 2, 2})), "no error");
  EXPECT_EQ(SurfaceError(ExtractBoundary(MakeBoxTetMesh({1, 1, 1}, {2, 2, 2})).surface), "no error");
}

TEST(MeshValidationTest, NonFiniteCoordinateNamesTheVertex) {
  auto m = MakeIcosphere(1.0, 1);
  m.vertices(17, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(SurfaceError(m), HasSubstr("liver.obj: vertex 17: non-finite coordinate"));
  auto t = MakeBoxTetMesh({1, 1, 1}, {1, 1, 1});
  t.vertices(3, 2) = std::numeric_limits<double>::infinity();
  EXPECT_THAT(VolumeError(t), HasSubstr("gallbladder.vtu: vertex 3: non-finite"));
}

TEST(MeshValidationTest, OutOfRangeIndexNamesTheElement) {
  auto m = MakeIcosphere(1.0, 1);
  m.triangles(5, 2) = 999;
  EXPECT_THAT(SurfaceError(m), HasSubstr("triangle 5: vertex index 999 out of range [0, 42)"));
  auto t = MakeBoxTetMesh({1, 1, 1}, {1, 1, 1});
  t.tets(2, 0) = -1;
  EXPECT_THAT(VolumeError(t), HasSubstr("tetrahedron 2: vertex index -1 out of range"));
}

TEST(MeshValidationTest, DegenerateAndInvertedTetsAreNamed) {
  auto t = MakeBoxTetMesh({1, 1, 1}, {1, 1, 1});
  std::swap(t.tets(4, 0), t.tets(4, 1));
  EXPECT_THAT(VolumeError(t), HasSubstr("tetrahedron 4: is inverted"));
  auto d = MakeBoxTetMesh({1, 1, 1}, {1, 1, 1});
  d.vertices.row(d.tets(1, 3)) = d.vertices.row(d.tets(1, 0)) * 0.5 + d.vertices.row(d.tets(1, 1)) * 0.5;
  // Flattening corner 3 onto edge (0, 1) makes tet 1 (and possibly others) degenerate.
  EXPECT_THAT(VolumeError(d), HasSubstr("is degenerate"));
  auto r = MakeBoxTetMesh({1, 1, 1}, {1, 1, 1});
  r.tets(3, 2) = r.tets(3, 1);
  EXPECT_THAT(VolumeError(r), HasSubstr("tetrahedron 3: repeats vertex"));
}

TEST(MeshValidationTest, DegenerateTriangleIsNamed) {
  auto m = MakeIcosphere(1.0, 1);
  m.vertices.row(m.triangles(9, 2)) = m.vertices.row(m.triangles(9, 0));
  EXPECT_THAT(SurfaceError(m, SurfaceRequirement::kAny), HasSubstr("is degenerate"));
}

TEST(MeshValidationTest, OpenSurfaceIsRejectedOnlyWhereClosedIsRequired) {
  auto m = MakeIcosphere(1.0, 1);
  TriangleMesh open = m;
  open.triangles = m.triangles.topRows(m.num_triangles() - 1);
  EXPECT_EQ(SurfaceError(open, SurfaceRequirement::kAny), "no error");
  EXPECT_THAT(SurfaceError(open), HasSubstr("is a boundary edge: surface is open"));
}

TEST(MeshValidationTest, InconsistentOrientationAndInwardNormals) {
  auto flipped_one = MakeIcosphere(1.0, 1);
  std::swap(flipped_one.triangles(7, 0), flipped_one.triangles(7, 1));
  EXPECT_THAT(SurfaceError(flipped_one), HasSubstr("orientation disagrees"));
  auto inward = MakeIcosphere(1.0, 1);
  inward.triangles.col(0).swap(inward.triangles.col(1));
  EXPECT_THAT(SurfaceError(inward), HasSubstr("normals point inward"));
}

TEST(MeshValidationTest, NonManifoldEdgeAndVertex) {
  // Two tetrahedron surfaces sharing one edge: that edge has four triangles.
  TriangleMesh twin;
  twin.vertices.resize(6, 3);
  twin.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.5, -1, -1, 0.6, 1, -1;
  twin.triangles.resize(8, 3);
  twin.triangles << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3,   // tet (0,1,2,3)
      0, 1, 4, 1, 5, 4, 0, 4, 5, 0, 5, 1;                // tet (0,1,4,5) shares edge (0,1)
  EXPECT_THAT(SurfaceError(twin), HasSubstr("shared by more than two triangles"));
  // Two closed tetrahedron surfaces touching at one vertex.
  TriangleMesh bowtie;
  bowtie.vertices.resize(7, 3);
  bowtie.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, -1, 0, 0, 0, -1, 0, 0, 0, -1;
  bowtie.triangles.resize(8, 3);
  bowtie.triangles << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3, 0, 5, 4, 0, 4, 6, 0, 6, 5, 4, 5, 6;
  EXPECT_THAT(SurfaceError(bowtie), HasSubstr("vertex 0: is non-manifold"));
}

/// A 2 x 2 x 2 box of unit size (27 vertices, vertex 13 inside, 26 the corner (1, 1, 1)) and one
/// more tet that touches it at `shared` corners only (vertex 26, or the edge (23, 26)).
TetrahedralMesh BoxWithTouchingTet(bool share_edge) {
  TetrahedralMesh m = MakeBoxTetMesh({1, 1, 1}, {2, 2, 2});
  const int n = m.num_vertices();
  m.vertices.conservativeResize(n + 3, 3);
  m.vertices.row(n) << 1.5, 1, 1.5;
  m.vertices.row(n + 1) << 1, 1.5, 1.5;
  m.vertices.row(n + 2) << 1.5, 1.5, 1;
  m.tets.conservativeResize(m.num_tets() + 1, 4);
  m.tets.row(m.num_tets() - 1) << 26, (share_edge ? 23 : n), n + 1, n + 2;
  if (SignedTetVolume(m, m.num_tets() - 1) < 0) std::swap(m.tets(m.num_tets() - 1, 2), m.tets(m.num_tets() - 1, 3));
  return m;
}

std::string BoundaryError(const TetrahedralMesh& m) {
  try {
    ValidateTetrahedralMesh(m, "gallbladder.vtu");
    ValidateTetMeshBoundary(m, "gallbladder.vtu");
  } catch (const MeshError& e) {
    return e.what();
  }
  return "no error";
}

TEST(MeshValidationTest, TetBoundaryErrorsGiveTheVolumesNumbers) {
  EXPECT_EQ(BoundaryError(MakeBoxTetMesh({1, 1, 1}, {2, 2, 2})), "no error");
  // On the boundary surface vertex 26 has another number (interior vertex 13 is not on it).
  EXPECT_EQ(BoundaryError(BoxWithTouchingTet(false)),
            "gallbladder.vtu: vertex 26: is non-manifold (its triangles form more than one fan)");
  EXPECT_THAT(BoundaryError(BoxWithTouchingTet(true)),
              ::testing::AnyOf(HasSubstr(": edge (23, 26) is shared by more than two triangles"),
                               HasSubstr(": edge (26, 23) is shared by more than two triangles")));
  EXPECT_THAT(BoundaryError(BoxWithTouchingTet(true)), ::testing::MatchesRegex(
                                                           "gallbladder.vtu: tetrahedron [0-9]+ face opposite corner [0-3]: .*"));
}

TEST(MeshValidationTest, EmptyMeshIsNamed) {
  EXPECT_THAT(SurfaceError(TriangleMesh{}), HasSubstr("liver.obj: mesh: has no vertices"));
}

}  // namespace
}  // namespace vesica::physics
