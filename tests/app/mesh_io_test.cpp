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

TEST_F(MeshIoTest, WrongCellTypeIsNamed) {
  const fs::path p = dir_ / "hex.vtk";
  std::ofstream(p) << "# vtk DataFile Version 3.0\nhex\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 8 double\n"
                      "0 0 0 1 0 0 1 1 0 0 1 0 0 0 1 1 0 1 1 1 1 0 1 1\nCELLS 1 9\n8 0 1 2 3 4 5 6 7\nCELL_TYPES 1\n12\n";
  EXPECT_THAT(ErrorOf([&] { ReadTetrahedralMesh(p); }), HasSubstr(p.string() + ": cell 0: VTK cell type 12 is not a tetrahedron"));
}

}  // namespace
}  // namespace vesica::app
