// Reruns the generator (about 5-10 s) into a temporary directory and checks that it reproduces
// the committed data/anatomy files: same counts, same volumes, same ports.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "anatomy_test_data.h"
#include "app/anatomy/anatomy_generator.h"
#include "app/mesh_io/mesh_io.h"

namespace vesica::app::anatomy::testing {
namespace {

std::string ReadText(const std::filesystem::path& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

TEST(AnatomyReproducibilityTest, GeneratorReproducesTheCommittedFiles) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("vesica_anatomy_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  std::filesystem::remove_all(dir);
  WriteAnatomy(GenerateAnatomy(AnatomyOptions{}), dir);

  const physics::TriangleMesh liver = ReadTriangleMesh(dir / "liver.vtk", physics::SurfaceRequirement::kClosed);
  const physics::TriangleMesh committed_liver = LoadLiver();
  EXPECT_EQ(liver.num_vertices(), committed_liver.num_vertices());
  EXPECT_EQ(liver.num_triangles(), committed_liver.num_triangles());
  EXPECT_NEAR(physics::EnclosedVolume(liver), physics::EnclosedVolume(committed_liver), 1e-12);
  EXPECT_EQ(liver.vertex_labels, committed_liver.vertex_labels);

  for (int nodes : {300, 600, 1000, 1600, 3000}) {
    const physics::TetrahedralMesh mesh = ReadTetrahedralMesh(dir / (GallbladderStem(nodes) + ".vtu"));
    const physics::TetrahedralMesh committed = LoadGallbladder(nodes);
    EXPECT_EQ(mesh.num_vertices(), committed.num_vertices()) << nodes;
    EXPECT_EQ(mesh.num_tets(), committed.num_tets()) << nodes;
    EXPECT_NEAR(physics::TotalVolume(mesh), physics::TotalVolume(committed), 1e-12) << nodes;
  }
  const physics::TriangleMesh wall = ReadTriangleMesh(dir / "abdominal_wall.vtk", physics::SurfaceRequirement::kAny);
  EXPECT_EQ(wall.num_vertices(), LoadAbdominalWall().num_vertices());
  EXPECT_EQ(ReadText(dir / "ports.toml"), ReadText(AnatomyFile("ports.toml")));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace vesica::app::anatomy::testing
