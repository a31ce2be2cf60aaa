// Organ scale: a mesh in the wrong units (a liver of 100 m) or with a vertex far away (1e30) is
// refused naming its extent, before anything is computed on it.
#include "physics/mesh/organ_scale.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

#include "physics/mesh/mesh_validation.h"
#include "physics/mesh/primitives.h"

namespace vesica::physics {
namespace {

using ::testing::HasSubstr;

std::string ScaleError(const Vertices& v) {
  try {
    CheckOrganScale(v, "liver.obj");
  } catch (const MeshError& e) {
    return e.what();
  }
  return "no error";
}

TEST(OrganScaleTest, OrganSizesPass) {
  EXPECT_EQ(ScaleError(MakeBoxTetMesh({0.2, 0.15, 0.08}, {2, 2, 2}).vertices), "no error");  // a liver
  EXPECT_EQ(ScaleError(MakeBoxTetMesh({kMinOrganExtent_m, 0.001, 0.001}, {1, 1, 1}).vertices), "no error");
  EXPECT_EQ(ScaleError(MakeBoxTetMesh({0.4, 0.17, kMaxOrganExtent_m}, {1, 1, 1}).vertices), "no error");
}

TEST(OrganScaleTest, LiverOfAHundredMetresIsWrongUnits) {
  EXPECT_EQ(ScaleError(MakeBoxTetMesh({100, 50, 20}, {1, 1, 1}).vertices),
            "liver.obj: wrong units or scale: the mesh spans 100 x 50 x 20 m (from (0, 0, 0) to (100, 50, 20)); "
            "an organ mesh spans 0.005 to 1.5 m, in metres (is the file in millimetres or centimetres?)");
}

TEST(OrganScaleTest, FarVertexAndTinyMeshAreRefused) {
  Vertices v = MakeBoxTetMesh({0.1, 0.1, 0.1}, {1, 1, 1}).vertices;
  v.row(3) << 1e30, 0, 0;
  EXPECT_THAT(ScaleError(v), HasSubstr("liver.obj: wrong units or scale: the mesh spans 1e+30 x 0.1 x 0.1 m"));
  EXPECT_THAT(ScaleError(MakeBoxTetMesh({2e-4, 1e-4, 1e-4}, {1, 1, 1}).vertices),
              HasSubstr("the mesh spans 0.0002 x 0.0001 x 0.0001 m"));
  // Overflowing extent (-1e308 to 1e308) is still named.
  v.row(2) << -1e308, 0, 0;
  v.row(3) << 1e308, 0, 0;
  EXPECT_THAT(ScaleError(v), HasSubstr("the mesh spans inf x 0.1 x 0.1 m"));
}

TEST(OrganScaleTest, NonFiniteVerticesAreLeftToValidation) {
  Vertices v = MakeBoxTetMesh({0.1, 0.1, 0.1}, {1, 1, 1}).vertices;
  v.row(3) << std::numeric_limits<double>::quiet_NaN(), 0, 0;
  EXPECT_EQ(ScaleError(v), "no error");
}

}  // namespace
}  // namespace vesica::physics
