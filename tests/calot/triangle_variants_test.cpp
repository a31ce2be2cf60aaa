// Anatomical variants come from data (issue 36): a short cystic duct, a low insertion running
// beside the common bile duct, an artery crossing in front of the common hepatic duct. Each
// builds, moves with the neck, divides cleanly between clips and is hidden by its fat layer.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "physics/calot/fat_layer.h"
#include "physics/calot/triangle_structures.h"

namespace vesica::physics::calot {
namespace {

constexpr int kDuct = 0, kArtery = 1, kBile = 3;

TriangleDescription ShortCysticDuct() {
  TriangleDescription d = DefaultTriangleDescription();
  const Eigen::Vector3d junction = d.tubes[kDuct].centreline_m.front();
  const Eigen::Vector3d toward_neck = (d.p_Neck_W_m - junction).normalized();
  d.p_Neck_W_m = junction + 0.007 * toward_neck;  // 7 mm: the gallbladder sits on the common duct
  d.tubes[kDuct].centreline_m = {junction, d.p_Neck_W_m};
  d.tubes[kArtery].centreline_m.back() = d.p_Neck_W_m + Eigen::Vector3d(-0.003, 0.002, 0.0);
  return d;
}

TriangleDescription LowInsertionBesideTheBileDuct() {
  TriangleDescription d = DefaultTriangleDescription();
  // The junction moves 20 mm down the common duct; the cystic duct runs 3 mm beside it.
  const auto& bile = d.tubes[kBile].centreline_m;
  const Eigen::Vector3d low = bile[1] + 0.5 * (bile[2] - bile[1]);
  const Eigen::Vector3d beside(-0.003, 0.0, 0.0);
  d.tubes[kDuct].centreline_m = {low, bile[1] + beside, bile[0] + beside, d.p_Neck_W_m};
  d.tubes[2].centreline_m = {d.tubes[2].centreline_m[0], d.tubes[2].centreline_m[1], bile[0], bile[1], low};
  d.tubes[kBile].centreline_m = {low, bile[2]};
  return d;
}

TriangleDescription ArteryInFront() {
  TriangleDescription d = DefaultTriangleDescription();
  // From the left of the common hepatic duct, 5 mm in front of it (toward the camera, +z), to the neck.
  const Eigen::Vector3d hepatic_middle = d.tubes[2].centreline_m[1];
  d.tubes[kArtery].centreline_m = {hepatic_middle + Eigen::Vector3d(0.012, 0.004, 0.004),
                                   hepatic_middle + Eigen::Vector3d(0.0, 0.0, 0.006),
                                   d.p_Neck_W_m + Eigen::Vector3d(-0.003, 0.003, 0.0)};
  return d;
}

void CheckVariant(const TriangleDescription& description, const std::string& name) {
  SCOPED_TRACE(name);
  TriangleStructures s(description);
  FatLayer fat(DefaultFatLayerDescription(description), s);
  for (int t = 0; t < s.num_tubes(); ++t) EXPECT_DOUBLE_EQ(fat.UncoveredFraction(t), 0.0) << t;
  for (int k = 1; k <= 200; ++k) {
    const double phase = 0.03 * k;
    s.Step(description.p_Neck_W_m + 0.004 * Eigen::Vector3d(std::sin(phase), 1.0 - std::cos(phase), 0.0));
    fat.Update(s);
  }
  const Eigen::Vector3d neck =
      description.p_Neck_W_m + 0.004 * Eigen::Vector3d(std::sin(6.0), 1.0 - std::cos(6.0), 0.0);
  EXPECT_LT((s.PositionAt(kDuct, s.TubeLength_m(kDuct)) - neck).norm(), 5e-4);
  for (const TubePiece& p : s.pieces()) ASSERT_TRUE(p.rod.positions_m().allFinite());
  // Clip twice on the patient's side, once on the gallbladder's, divide between: dry.
  for (int tube : {kDuct, kArtery}) {
    const double l = s.TubeLength_m(tube);
    for (double f : {0.2, 0.45, 0.85}) ASSERT_EQ(s.PlaceClip(tube, f * l), ToolActionResult::kDone) << tube;
    ASSERT_EQ(s.Cut(tube, 0.65 * l), ToolActionResult::kDone) << tube;
  }
  for (int k = 0; k < 50; ++k) s.Step(description.p_Neck_W_m + Eigen::Vector3d(-0.01, 0.01, 0.0));
  EXPECT_TRUE(s.Leaks().empty());
  for (const TubePiece& p : s.pieces()) ASSERT_TRUE(p.rod.positions_m().allFinite());
  // Cutting the common bile duct (the injury) leaks bile from both stumps.
  ASSERT_EQ(s.Cut(kBile, 0.5 * s.TubeLength_m(kBile)), ToolActionResult::kDone);
  EXPECT_TRUE(s.BileLeaking());
  EXPECT_EQ(s.Leaks().size(), 2u);
}

TEST(TriangleVariantsTest, ShortCysticDuct) { CheckVariant(ShortCysticDuct(), "short cystic duct"); }
TEST(TriangleVariantsTest, LowInsertionBesideTheBileDuct) {
  CheckVariant(LowInsertionBesideTheBileDuct(), "low insertion");
}
TEST(TriangleVariantsTest, ArteryCrossingInFront) { CheckVariant(ArteryInFront(), "artery in front"); }

}  // namespace
}  // namespace vesica::physics::calot
