// The shipped default scenario loads, and its meshes load and validate through the VTK adapter.
#include <gtest/gtest.h>

#include "app/mesh_io/mesh_io.h"
#include "app/scenario/scenario_loader.h"
#include "physics/mesh/mesh_validation.h"

namespace vesica::app {
namespace {

TEST(DefaultScenarioTest, LoadsWithPaperMaterialsAndTwoInstruments) {
  const Scenario s = LoadScenario(DefaultScenarioPath());
  EXPECT_DOUBLE_EQ(s.liver.material.youngs_modulus_Pa, 170e3);  // gallbladder paper Table 1
  EXPECT_DOUBLE_EQ(s.liver.material.poisson_ratio, 0.4);
  EXPECT_DOUBLE_EQ(s.gallbladder.material.youngs_modulus_Pa, 2.3e3);
  EXPECT_DOUBLE_EQ(s.gallbladder.material.poisson_ratio, 0.45);
  ASSERT_EQ(s.instruments.size(), 2u);
  EXPECT_EQ(s.instruments[0].kind, InstrumentKind::kGrasper);
  EXPECT_EQ(s.instruments[1].kind, InstrumentKind::kCauteryHook);
  for (const auto& i : s.instruments) EXPECT_EQ(i.input, InputKind::kKeyboard);  // no hardware by default
}

TEST(DefaultScenarioTest, MeshesLoadAndTheLiverHasAFixedRegion) {
  const Scenario s = LoadScenario(DefaultScenarioPath());
  const auto liver = ReadTriangleMesh(s.liver.surface_mesh, physics::SurfaceRequirement::kClosed);
  ASSERT_EQ(liver.vertex_labels.size(), liver.num_vertices());
  int fixed = 0, bed = 0;
  for (int v = 0; v < liver.num_vertices(); ++v) {
    fixed += (liver.vertex_labels[v] & physics::kLabelFixed) != 0;
    bed += (liver.vertex_labels[v] & physics::kLabelGallbladderBed) != 0;
  }
  EXPECT_GT(fixed, 0);
  EXPECT_GT(bed, 0);
  const auto gallbladder = ReadTetrahedralMesh(s.gallbladder.volume_mesh);
  EXPECT_GT(gallbladder.num_tets(), 0);
  const auto wall = ReadTriangleMesh(s.abdominal_wall.surface_mesh, physics::SurfaceRequirement::kAny);
  EXPECT_GT(wall.num_triangles(), 0);
}

}  // namespace
}  // namespace vesica::app
