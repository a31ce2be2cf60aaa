// The VTK mesh adapter: every format round-trips, labels survive, and broken files give errors
// that name the file and the element.
#include "app/mesh_io/mesh_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <limits>

#include "physics/mesh/primitives.h"

namespace vesica::app {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class MeshIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vesica_mesh_io_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  template <typename Read>
  std::string ErrorOf(Read read) {
    try {
      read();
    } catch (const physics::MeshError& e) {
      return e.what();
    }
    return "no error";
  }

  fs::path dir_;
};

TEST_F(MeshIoTest, SurfaceFormatsRoundTrip) {
  physics::TriangleMesh sphere = physics::MakeIcosphere(0.05, 2);
  sphere.vertex_labels = Eigen::VectorXi::LinSpaced(sphere.num_vertices(), 0, 3);
  for (const char* ext : {".vtk", ".vtp", ".obj", ".stl", ".ply"}) {
    const fs::path p = dir_ / (std::string("sphere") + ext);
    WriteTriangleMesh(sphere, p);
    const auto back = ReadTriangleMesh(p, physics::SurfaceRequirement::kClosed);
    EXPECT_EQ(back.num_triangles(), sphere.num_triangles()) << ext;
    // STL stores triangles, not shared vertices; VTK's reader merges them back.
    EXPECT_EQ(back.num_vertices(), sphere.num_vertices()) << ext;
    EXPECT_NEAR(physics::EnclosedVolume(back), physics::EnclosedVolume(sphere), 1e-6 * physics::EnclosedVolume(sphere))
        << ext;
  }
  const auto labelled = ReadTriangleMesh(dir_ / "sphere.vtk", physics::SurfaceRequirement::kClosed);
  EXPECT_EQ(labelled.vertex_labels, sphere.vertex_labels);
}

TEST_F(MeshIoTest, TetFormatsRoundTripExactly) {
  const auto box = physics::MakeBoxTetMesh({0.08, 0.03, 0.03}, {4, 2, 2});
  for (const char* ext : {".vtu", ".vtk"}) {
    const fs::path p = dir_ / (std::string("box") + ext);
    WriteTetrahedralMesh(box, p);
    const auto back = ReadTetrahedralMesh(p);
    EXPECT_EQ(back.tets, box.tets) << ext;
    EXPECT_TRUE(back.vertices.isApprox(box.vertices, 1e-12)) << ext;
  }
}

TEST_F(MeshIoTest, NonFiniteVertexNamesFileAndVertex) {
  auto sphere = physics::MakeIcosphere(0.05, 1);
  sphere.vertices(7, 0) = std::numeric_limits<double>::quiet_NaN();
  const fs::path p = dir_ / "nan.vtp";  // binary XML keeps the NaN
  WriteTriangleMesh(sphere, p);
  EXPECT_THAT(ErrorOf([&] { ReadTriangleMesh(p, physics::SurfaceRequirement::kAny); }),
              HasSubstr(p.string() + ": vertex 7: non-finite coordinate"));
  // In ASCII the NaN stops VTK's legacy reader: the file is rejected in VTK's words, not truncated.
  const fs::path ascii = dir_ / "nan.vtk";
  WriteTriangleMesh(sphere, ascii);
  EXPECT_THAT(ErrorOf([&] { ReadTriangleMesh(ascii, physics::SurfaceRequirement::kAny); }),
              HasSubstr(ascii.string() + ": cannot be read: "));
}

TEST_F(MeshIoTest, VtksOwnReasonIsKept) {
  // It once ended at "cannot be read: ": VTK's text was cut at its trailing blank line.
  auto sphere = physics::MakeIcosphere(0.05, 1);
  sphere.vertices(7, 0) = std::numeric_limits<double>::quiet_NaN();
  const fs::path p = dir_ / "nan.vtk";  // the NaN stops VTK's legacy ASCII reader
  WriteTriangleMesh(sphere, p);
  EXPECT_EQ(ErrorOf([&] { ReadTriangleMesh(p, physics::SurfaceRequirement::kAny); }),
            p.string() +
                ": cannot be read: Error reading ascii data. Possible mismatch of datasize with declaration. (then: "
                "Unrecognized keyword: nan)");
  // A POINTS section cut short: VTK only warns, and returned garbage coordinates (1e299) as points.
  const fs::path short_points = dir_ / "short_points.vtk";
  std::ofstream(short_points) << "# vtk DataFile Version 3.0\nshort\nASCII\nDATASET POLYDATA\nPOINTS 4 double\n"
                                 "0 0 0 0.1 0 0\n";
  EXPECT_EQ(ErrorOf([&] { ReadTriangleMesh(short_points, physics::SurfaceRequirement::kAny); }),
            short_points.string() +
                ": cannot be read: Error reading ascii data. Possible mismatch of datasize with declaration.");
  // The reason of a helper nobody observes (the XML parser), not the reader's summary.
  const fs::path xml = dir_ / "not_xml.vtp";
  std::ofstream(xml) << "this is not XML\n";
  EXPECT_EQ(ErrorOf([&] { ReadTriangleMesh(xml, physics::SurfaceRequirement::kAny); }),
            xml.string() + ": cannot be read: Error parsing XML in stream at line 1, column 0, byte index 0: syntax error");
}

/// A closed cube of side 0.1 m as exporters write it: eight `v`, one `vn` a face, and faces
/// `f v//vn` whose normal index differs from the vertex index (VTK then splits every corner).
constexpr const char* kCubeObjWithFaceNormals = R"(# cube
v 0 0 0
v 0.1 0 0
v 0.1 0.1 0
v 0 0.1 0
v 0 0 0.1
v 0.1 0 0.1
v 0.1 0.1 0.1
v 0 0.1 0.1
vn 0 0 -1
vn 0 0 1
vn 0 -1 0
vn 1 0 0
vn 0 1 0
vn -1 0 0
f 1//1 3//1 2//1
f 1//1 4//1 3//1
f 5//2 6//2 7//2
f 5//2 7//2 8//2
f 1//3 2//3 6//3
f 1//3 6//3 5//3
f 2//4 3//4 7//4
f 2//4 7//4 6//4
f 3//5 4//5 8//5
f 3//5 8//5 7//5
f 4//6 1//6 5//6
f 4//6 5//6 8//6
)";

TEST_F(MeshIoTest, ObjWithPerFaceNormalsIsTheClosedMeshItIs) {
  const fs::path p = dir_ / "cube.obj";
  std::ofstream(p) << kCubeObjWithFaceNormals;
  const auto cube = ReadTriangleMesh(p, physics::SurfaceRequirement::kClosed);
  EXPECT_EQ(cube.num_vertices(), 8);
  EXPECT_EQ(cube.num_triangles(), 12);
  EXPECT_NEAR(physics::EnclosedVolume(cube), 1e-3, 1e-9);  // VTK's OBJ reader keeps floats
  // The vertices keep the file's numbers: v line k is vertex k - 1.
  EXPECT_TRUE(cube.vertices.row(6).isApprox(Eigen::RowVector3d(0.1, 0.1, 0.1), 1e-7)) << cube.vertices;
  EXPECT_EQ(cube.triangles.row(0), Eigen::RowVector3i(0, 2, 1));

  // The same with texture coordinates (`f v/vt/vn`), relative indices and CRLF line ends.
  std::string text = kCubeObjWithFaceNormals;
  text.replace(text.find("vn 0 0 -1"), 0, "vt 0 0\nvt 1 0\nvt 0 1\n");
  text.replace(text.find("f 1//1 3//1 2//1"), 16, "f -8/1/1 -6/2/1 -7/3/1");
  for (std::size_t at = 0; (at = text.find("//", at)) != std::string::npos;) text.replace(at, 2, "/2/");
  for (std::size_t at = 0; (at = text.find('\n', at)) != std::string::npos; at += 2) text.replace(at, 1, "\r\n");
  const fs::path textured = dir_ / "cube_textured.obj";
  std::ofstream(textured) << text;
  const auto again = ReadTriangleMesh(textured, physics::SurfaceRequirement::kClosed);
  EXPECT_EQ(again.triangles, cube.triangles);
  EXPECT_EQ(again.vertices, cube.vertices);
}

TEST_F(MeshIoTest, SelfIntersectingObjIsRefusedNamingTheFacePairs) {
  // Two closed tetrahedra, the second's corner inside the first.
  const fs::path p = dir_ / "two_tets.obj";
  std::ofstream(p) << "v 0 0 0\nv 0.01 0 0\nv 0 0.01 0\nv 0 0 0.01\n"
                      "v 0.002 0.002 0.002\nv 0.012 0.002 0.002\nv 0.002 0.012 0.002\nv 0.002 0.002 0.012\n"
                      "vn 0 0 1\n"
                      "f 1//1 3//1 2//1\nf 1//1 2//1 4//1\nf 1//1 4//1 3//1\nf 2//1 3//1 4//1\n"
                      "f 5//1 7//1 6//1\nf 5//1 6//1 8//1\nf 5//1 8//1 7//1\nf 6//1 7//1 8//1\n";
  EXPECT_EQ(ErrorOf([&] { ReadTriangleMesh(p, physics::SurfaceRequirement::kClosed); }),
            p.string() + ": mesh: intersects itself: 3 pairs of triangles cross: triangle 3 and triangle 4; "
                         "triangle 3 and triangle 5; triangle 3 and triangle 6");
}

TEST_F(MeshIoTest, TetBoundaryErrorsGiveTheFilesNumbers) {
  // A 2 x 2 x 2 box (vertex 13 inside) and a tet touching it at corner vertex 26 only.
  auto box = physics::MakeBoxTetMesh({0.1, 0.1, 0.1}, {2, 2, 2});
  box.vertices.conservativeResize(30, 3);
  box.vertices.bottomRows(3) << 0.15, 0.1, 0.15, 0.1, 0.15, 0.15, 0.15, 0.15, 0.1;
  box.tets.conservativeResize(box.num_tets() + 1, 4);
  box.tets.bottomRows(1) << 26, 27, 29, 28;
  const fs::path p = dir_ / "touching.vtu";
  WriteTetrahedralMesh(box, p);
  EXPECT_EQ(ErrorOf([&] { ReadTetrahedralMesh(p); }),
            p.string() + ": vertex 26: is non-manifold (its triangles form more than one fan)");
}

TEST_F(MeshIoTest, WrongUnitsAreRefusedNamingTheExtent) {
  // A liver of 100 m (a file in centimetres): refused before any check that computes on it.
  const fs::path liver = dir_ / "liver_cm.vtk";
  WriteTriangleMesh(physics::MakeIcosphere(50, 1), liver);
  EXPECT_THAT(ErrorOf([&] { ReadTriangleMesh(liver, physics::SurfaceRequirement::kClosed); }),
              HasSubstr(liver.string() + ": wrong units or scale: the mesh spans 100 x "));
  auto far = physics::MakeIcosphere(0.05, 1);
  far.vertices.row(5) << 1e30, 0, 0;
  const fs::path p = dir_ / "far.vtp";
  WriteTriangleMesh(far, p);
  EXPECT_THAT(ErrorOf([&] { ReadTriangleMesh(p, physics::SurfaceRequirement::kAny); }),
              HasSubstr(p.string() + ": wrong units or scale: the mesh spans 1e+30 x 0.1"));
  const fs::path tets = dir_ / "box_mm.vtu";
  WriteTetrahedralMesh(physics::MakeBoxTetMesh({80, 30, 30}, {2, 1, 1}), tets);
  EXPECT_THAT(ErrorOf([&] { ReadTetrahedralMesh(tets); }),
              HasSubstr(tets.string() + ": wrong units or scale: the mesh spans 80 x 30 x 30 m"));
}

TEST_F(MeshIoTest, InvertedTetNamesFileAndTet) {
  auto box = physics::MakeBoxTetMesh({1, 1, 1}, {1, 1, 1});
  std::swap(box.tets(2, 0), box.tets(2, 1));
  const fs::path p = dir_ / "inverted.vtu";
  WriteTetrahedralMesh(box, p);
  EXPECT_THAT(ErrorOf([&] { ReadTetrahedralMesh(p); }), HasSubstr(p.string() + ": tetrahedron 2: is inverted"));
}

TEST_F(MeshIoTest, OpenSurfaceRejectedWhereClosedIsRequired) {
  auto sphere = physics::MakeIcosphere(0.05, 1);
  sphere.triangles.conservativeResize(sphere.num_triangles() - 1, 3);
  const fs::path p = dir_ / "open.obj";
  WriteTriangleMesh(sphere, p);
  EXPECT_EQ(ErrorOf([&] { ReadTriangleMesh(p, physics::SurfaceRequirement::kAny); }), "no error");
  EXPECT_THAT(ErrorOf([&] { ReadTriangleMesh(p, physics::SurfaceRequirement::kClosed); }),
              HasSubstr(p.string() + ": triangle"));
}

TEST_F(MeshIoTest, OutOfRangeIndexInAHandWrittenFile) {
  const fs::path p = dir_ / "bad_index.vtk";
  std::ofstream(p) << "# vtk DataFile Version 3.0\nbad\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n"
                      "0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 5\n4 0 1 2 9\nCELL_TYPES 1\n10\n";
  EXPECT_THAT(ErrorOf([&] { ReadTetrahedralMesh(p); }), HasSubstr(p.string()));
}

TEST_F(MeshIoTest, MissingFileAndUnknownFormat) {
  EXPECT_THAT(ErrorOf([&] { ReadTetrahedralMesh(dir_ / "absent.vtu"); }),
              HasSubstr("absent.vtu: cannot open file for reading"));
  const fs::path p = dir_ / "mesh.xyz";
  std::ofstream(p) << "1 2 3\n";
  EXPECT_THAT(ErrorOf([&] { ReadTriangleMesh(p, physics::SurfaceRequirement::kAny); }),
              HasSubstr("mesh.xyz: unsupported mesh format '.xyz'"));
}

TEST_F(MeshIoTest, DirectoryIsNamedAsSuch) {
  const fs::path d = dir_ / "liver.vtk";
  fs::create_directories(d);
  EXPECT_EQ(ErrorOf([&] { ReadTriangleMesh(d, physics::SurfaceRequirement::kAny); }),
            d.string() + ": is a directory, not a mesh file");
  const fs::path g = dir_ / "gallbladder.vtu";
  fs::create_directories(g);
  EXPECT_EQ(ErrorOf([&] { ReadTetrahedralMesh(g); }), g.string() + ": is a directory, not a mesh file");
}

TEST_F(MeshIoTest, WrongCellTypeIsNamed) {
  const fs::path p = dir_ / "hex.vtk";
  std::ofstream(p) << "# vtk DataFile Version 3.0\nhex\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 8 double\n"
                      "0 0 0 1 0 0 1 1 0 0 1 0 0 0 1 1 0 1 1 1 1 0 1 1\nCELLS 1 9\n8 0 1 2 3 4 5 6 7\nCELL_TYPES 1\n12\n";
  EXPECT_THAT(ErrorOf([&] { ReadTetrahedralMesh(p); }), HasSubstr(p.string() + ": cell 0: VTK cell type 12 is not a tetrahedron"));
}

}  // namespace
}  // namespace vesica::app
