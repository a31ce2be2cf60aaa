#include "fx/burn_map.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "fx_test_meshes.h"

namespace vesica::fx {
namespace {

using ::testing::HasSubstr;

BurnParams Params(double rate, double radius, double threshold) {
  BurnParams p;
  p.rate_per_s = rate;
  p.spread_radius_m = radius;
  p.damage_threshold = threshold;
  return p;
}

TEST(BurnMapTest, AccumulatesLinearlyAtContactAndFallsOffLinearlyWithCentroidDistance) {
  BurnMap map("liver", testing::MakeStrip(), Params(0.5, 1.0, 1.0));
  const double dt = 0.125;
  for (int k = 1; k <= 4; ++k) {
    map.Burn(1, dt, k * dt);
    EXPECT_DOUBLE_EQ(map.level(1), k * 0.5 * dt) << "step " << k;
  }
  const double contact = 4 * 0.5 * dt;  // 0.25
  // T0 centroid is sqrt(2)/3 from T1's, T2's sqrt(5)/3, T3's exactly 1 (= radius, no gain).
  EXPECT_DOUBLE_EQ(map.level(0), contact * (1 - std::sqrt(2.0) / 3));
  EXPECT_DOUBLE_EQ(map.level(2), contact * (1 - std::sqrt(5.0) / 3));
  EXPECT_EQ(map.level(3), 0.0);
  EXPECT_EQ(map.level(4), 0.0);
  EXPECT_EQ(map.level(5), 0.0);
  // The renderer's float mirror matches.
  ASSERT_EQ(map.levels().size(), 6u);
  EXPECT_EQ(map.levels()[0], static_cast<float>(map.level(0)));
  EXPECT_EQ(map.levels()[1], static_cast<float>(contact));
}

TEST(BurnMapTest, SaturatesAtOne) {
  BurnMap map("liver", testing::MakeStrip(), Params(2.0, 1.0, 1.0));
  for (int k = 0; k < 100; ++k) map.Burn(1, 0.1, 0.1 * k);
  EXPECT_EQ(map.level(1), 1.0);
  EXPECT_EQ(map.level(0), 1.0);  // neighbours saturate too, never beyond
  for (float level : map.levels()) EXPECT_LE(level, 1.0f);
  EXPECT_EQ(map.level(3), 0.0);
}

TEST(BurnMapTest, SpreadFollowsTheSurfaceNotTheAir) {
  // Two triangles 1 mm apart but sharing no edge: the spread must not jump the gap.
  physics::TriangleMesh mesh;
  mesh.vertices.resize(6, 3);
  mesh.vertices << 0, 0, 0, 0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.001, 0.01, 0, 0.001, 0, 0.01, 0.001;
  mesh.triangles.resize(2, 3);
  mesh.triangles << 0, 1, 2, 3, 4, 5;
  BurnMap map("gallbladder", mesh, Params(1.0, 0.01, 1.0));
  map.Burn(0, 0.5, 0.5);
  EXPECT_DOUBLE_EQ(map.level(0), 0.5);
  EXPECT_EQ(map.level(1), 0.0);
}

TEST(BurnMapTest, RecordsDamageOnlyStrictlyPastTheThreshold) {
  BurnMap map("liver", testing::MakeStrip(), Params(0.5, 1.0, 0.5));
  for (int k = 1; k <= 4; ++k) map.Burn(1, 0.25, 0.25 * k);
  EXPECT_EQ(map.level(1), 0.5);  // exactly at the threshold: not damage
  EXPECT_TRUE(map.damage_events().empty());
  EXPECT_EQ(map.damaged_area_m2(), 0.0);

  map.Burn(1, 0.25, 1.25);
  ASSERT_EQ(map.damage_events().size(), 1u);
  EXPECT_EQ(map.damage_events()[0].element, 1);
  EXPECT_EQ(map.damage_events()[0].time_s, 1.25);
  EXPECT_EQ(map.damage_events()[0].level, 0.625);
  EXPECT_DOUBLE_EQ(map.damaged_area_m2(), 0.5);

  // Burning on: T1 is not recorded twice; T0 joins when it crosses (0.5 / (1 - sqrt2/3) s of
  // contact in total, i.e. on step 8 at 0.25 s a step).
  for (int k = 6; k <= 8; ++k) map.Burn(1, 0.25, 0.25 * k);
  ASSERT_EQ(map.damage_events().size(), 2u);
  EXPECT_EQ(map.damage_events()[1].element, 0);
  EXPECT_EQ(map.damage_events()[1].time_s, 2.0);
  EXPECT_DOUBLE_EQ(map.damaged_area_m2(), 1.0);
}

TEST(BurnMapTest, MembraneMapRecordsNoDamage) {
  BurnParams p = Params(1.0, 1.0, 0.1);
  p.records_damage = false;
  BurnMap map("membrane", testing::MakeStrip(), p);
  map.Burn(2, 1.0, 1.0);
  EXPECT_EQ(map.level(2), 1.0);
  EXPECT_TRUE(map.damage_events().empty());
  EXPECT_EQ(map.damaged_area_m2(), 0.0);
}

TEST(BurnMapTest, UpdateGeometryMovesTheSpread) {
  BurnMap map("liver", testing::MakeStrip(), Params(1.0, 1.0, 1.0));
  physics::Vertices stretched = testing::MakeStrip().vertices;
  stretched.col(0) *= 3.0;  // T0 and T1 centroids now sqrt(1 + 1/9) > 1 apart
  map.UpdateGeometry(stretched);
  map.Burn(1, 0.5, 0.5);
  EXPECT_EQ(map.level(1), 0.5);
  EXPECT_EQ(map.level(0), 0.0);
}

TEST(BurnMapTest, RejectsBadInputNamingTheMapAndField) {
  BurnMap map("liver", testing::MakeStrip(), Params(1.0, 1.0, 0.5));
  try {
    map.Burn(6, 0.1, 0.1);
    FAIL() << "element 6 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("BurnMap 'liver': element 6 out of range [0, 6)"));
  }
  EXPECT_THROW(map.Burn(-1, 0.1, 0.1), std::invalid_argument);
  try {
    map.Burn(0, -0.1, 0.1);
    FAIL() << "negative dt accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("dt_s must be finite and >= 0"));
  }
  EXPECT_THROW(map.Burn(0, std::nan(""), 0.1), std::invalid_argument);
  for (int f = 0; f < 6; ++f) EXPECT_EQ(map.level(f), 0.0) << "rejected input changed state";

  EXPECT_THAT([] { BurnMap("gb", testing::MakeStrip(), Params(0.0, 1.0, 0.5)); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("rate_per_s")));
  EXPECT_THAT([] { BurnMap("gb", testing::MakeStrip(), Params(1.0, 1.0, 1.5)); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("damage_threshold")));
  physics::TriangleMesh broken = testing::MakeStrip();
  broken.triangles(3, 1) = 8;
  EXPECT_THAT([&] { BurnMap("gb", broken, Params(1.0, 1.0, 0.5)); },
              ::testing::ThrowsMessage<std::invalid_argument>(
                  HasSubstr("BurnMap 'gb': triangle 3: vertex 8 out of range [0, 8)")));
  EXPECT_THAT([&] { map.UpdateGeometry(physics::Vertices::Zero(5, 3)); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("got 5 vertices")));
}

}  // namespace
}  // namespace vesica::fx
