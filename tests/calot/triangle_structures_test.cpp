// The triangle's tubes with clips and cuts: clips ride on their material point, a cut makes two
// rods that move apart, tool queries find the right tube (docs/calot.md).
#include "physics/calot/triangle_structures.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace vesica::physics::calot {
namespace {

constexpr int kDuct = 0, kArtery = 1, kHepatic = 2, kBile = 3;  // DefaultTriangleDescription's order

/// The neck's scripted path: a 10 mm circle in two seconds, from its rest position.
Eigen::Vector3d NeckAt(const TriangleStructures& s, int step) {
  const double t = step * s.description().rod_settings.time_step_s;
  const double phase = 2.0 * std::numbers::pi * t / 2.0;
  return s.description().p_Neck_W_m +
         0.005 * Eigen::Vector3d(1.0 - std::cos(phase), std::sin(phase), 0.3 * std::sin(phase));
}

/// The point at s on the piece's current nodes, interpolated here independently of the model.
Eigen::Vector3d Interpolated(const TubeRod& rod, double s) {
  const std::vector<double>& sc = rod.material_coordinates_m();
  for (std::size_t i = 0; i + 1 < sc.size(); ++i)
    if (s >= sc[i] && s <= sc[i + 1]) {
      const double f = (s - sc[i]) / (sc[i + 1] - sc[i]);
      return ((1 - f) * rod.positions_m().row(static_cast<Eigen::Index>(i)) +
              f * rod.positions_m().row(static_cast<Eigen::Index>(i) + 1))
          .transpose();
    }
  ADD_FAILURE() << "s = " << s << " is not on this piece";
  return Eigen::Vector3d::Zero();
}

const TubePiece& PieceHolding(const TriangleStructures& s, int tube, double at) {
  for (const TubePiece& p : s.pieces())
    if (p.tube == tube && at >= p.rod.start_coordinate_m() && at <= p.rod.end_coordinate_m()) return p;
  throw std::logic_error("no piece");
}

TEST(TriangleStructuresTest, DefaultTriangleHasFourTubesOfRealisticSizeAtRest) {
  TriangleStructures s(DefaultTriangleDescription());
  ASSERT_EQ(s.num_tubes(), 4);
  EXPECT_NEAR(2 * s.description().tubes[kDuct].material.outer_radius_m, 0.003, 1e-9);
  EXPECT_NEAR(2 * s.description().tubes[kArtery].material.outer_radius_m, 0.002, 1e-9);
  EXPECT_NEAR(2 * s.description().tubes[kBile].material.outer_radius_m, 0.0065, 1e-9);
  for (int t = 0; t < 4; ++t) {
    EXPECT_GT(s.TubeLength_m(t), 0.04) << t;
    EXPECT_LT(s.TubeLength_m(t), 0.06) << t;
  }
  for (int k = 0; k < 50; ++k) s.Step(s.description().p_Neck_W_m);  // nothing moves without input
  for (const TubePiece& p : s.pieces()) EXPECT_LT((p.rod.positions_m() - p.rod.rest_points_m()).norm(), 1e-9);
  EXPECT_LT(s.NeckForce_N().norm(), 1e-9);
}

TEST(TriangleStructuresTest, AClipStaysAtItsMaterialPointThroughAScriptedMotion) {
  TriangleStructures s(DefaultTriangleDescription());
  const double at = 0.6 * s.TubeLength_m(kDuct);
  ASSERT_EQ(s.PlaceClip(kDuct, at), ToolActionResult::kDone);
  const Eigen::Vector3d start = s.ClipPosition(0);
  double farthest = 0.0;
  for (int k = 1; k <= 400; ++k) {
    s.Step(NeckAt(s, k));
    if (k == 200) {  // a cut on its patient's side
      ASSERT_EQ(s.Cut(kDuct, 0.3 * s.TubeLength_m(kDuct)), ToolActionResult::kDone);
    }
    const Eigen::Vector3d clip = s.ClipPosition(0);
    ASSERT_LT((clip - Interpolated(PieceHolding(s, kDuct, at).rod, at)).norm(), 1e-12) << "step " << k;
    // Still that material point: the share of the piece's current arc between the clip and the
    // neck end stays the rest share (the axial strain is about uniform along a tube).
    const TubeRod& rod = PieceHolding(s, kDuct, at).rod;
    const auto [i, f] = rod.SegmentAt(at);
    double beyond = (1 - f) * (rod.positions_m().row(i + 1) - rod.positions_m().row(i)).norm(), total = 0.0;
    for (int j = 0; j + 1 < rod.num_nodes(); ++j) {
      const double segment = (rod.positions_m().row(j + 1) - rod.positions_m().row(j)).norm();
      total += segment;
      if (j > i) beyond += segment;
    }
    const double rest_share = (rod.end_coordinate_m() - at) / (rod.end_coordinate_m() - rod.start_coordinate_m());
    EXPECT_NEAR(beyond / total, rest_share, 0.005) << "step " << k;
    farthest = std::max(farthest, (clip - start).norm());
  }
  EXPECT_GT(farthest, 0.004);  // it moved with the tube
  EXPECT_EQ(s.pieces().size(), 5u);
}

TEST(TriangleStructuresTest, ACutTubesTwoEndsMoveIndependently) {
  TriangleStructures whole(DefaultTriangleDescription()), cut(DefaultTriangleDescription());
  const double at = 0.5 * cut.TubeLength_m(kDuct);
  ASSERT_EQ(cut.Cut(kDuct, at), ToolActionResult::kDone);
  const TubePiece* patient = nullptr;
  const TubePiece* gallbladder = nullptr;
  for (const TubePiece& p : cut.pieces())
    if (p.tube == kDuct) (p.starts_at_cut ? gallbladder : patient) = &p;
  ASSERT_TRUE(patient && gallbladder);
  ASSERT_TRUE(patient->ends_at_cut);
  const Eigen::Vector3d patient_end0 = patient->rod.positions_m().bottomRows<1>().transpose();
  const Eigen::Vector3d gallbladder_end0 = gallbladder->rod.positions_m().topRows<1>().transpose();
  const Eigen::Vector3d whole_middle0 = whole.PositionAt(kDuct, at);
  // The neck pulls 10 mm away: the gallbladder's stump follows, the patient's does not.
  const Eigen::Vector3d pulled = cut.description().p_Neck_W_m + Eigen::Vector3d(-0.006, 0.008, 0.0);
  for (int k = 0; k < 200; ++k) {
    cut.Step(pulled);
    whole.Step(pulled);
  }
  patient = gallbladder = nullptr;
  for (const TubePiece& p : cut.pieces())
    if (p.tube == kDuct) (p.starts_at_cut ? gallbladder : patient) = &p;
  EXPECT_GT((gallbladder->rod.positions_m().topRows<1>().transpose() - gallbladder_end0).norm(), 0.005);
  EXPECT_LT((patient->rod.positions_m().bottomRows<1>().transpose() - patient_end0).norm(), 1e-6);
  EXPECT_GT((whole.PositionAt(kDuct, at) - whole_middle0).norm(), 0.002);  // uncut, the middle followed
  // A tool pushes the patient's stump: the gallbladder's does not follow.
  const Eigen::Vector3d gallbladder_end1 = gallbladder->rod.positions_m().topRows<1>().transpose();
  const Eigen::Vector3d stump = cut.PositionAt(kDuct, at - 0.004);
  for (int k = 0; k < 40; ++k) {
    const Eigen::Vector3d tip = stump + Eigen::Vector3d(0.0, 0.0, 0.004 - 0.0001 * k);
    cut.PushByTip(tip, 0.002);
    cut.Step(pulled);
  }
  EXPECT_GT((cut.PositionAt(kDuct, at - 0.004) - stump).norm(), 0.001);
  EXPECT_LT((gallbladder->rod.positions_m().topRows<1>().transpose() - gallbladder_end1).norm(), 1e-6);
}

TEST(TriangleStructuresTest, TheNeckIsPulledBackByTheTubes) {
  TriangleStructures s(DefaultTriangleDescription());
  const Eigen::Vector3d shift(-0.004, 0.010, 0.002);
  for (int k = 0; k < 100; ++k) s.Step(s.description().p_Neck_W_m + shift);
  EXPECT_LT(s.NeckForce_N().dot(shift), 0.0);
  EXPECT_GT(s.NeckForce_N().norm(), 1e-3);
}

TEST(TriangleStructuresTest, AJawSegmentFindsTheTubeAndMaterialPointItCrosses) {
  TriangleStructures s(DefaultTriangleDescription());
  const double at = 0.015;
  const Eigen::Vector3d on_artery = s.PositionAt(kArtery, at);
  const Eigen::Vector3d tangent = (s.PositionAt(kArtery, at + 0.001) - s.PositionAt(kArtery, at - 0.001)).normalized();
  const Eigen::Vector3d across = tangent.unitOrthogonal();
  const auto hit = s.NearestToSegment(on_artery - 0.003 * across, on_artery + 0.003 * across, 0.001);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->tube, kArtery);
  EXPECT_NEAR(hit->s_m, at, 1e-6);
  EXPECT_LT(hit->surface_gap_m, 0.0);
  // Far from every tube: nothing.
  EXPECT_FALSE(s.NearestToSegment(on_artery + 0.05 * across, on_artery + 0.06 * across, 0.001).has_value());
  // A ray from above the common bile duct's middle, pointing down at it.
  const Eigen::Vector3d cbd = s.PositionAt(kBile, 0.025);
  const auto ray_hit = s.NearestToSegment(cbd + Eigen::Vector3d(0, 0, 0.03), cbd - Eigen::Vector3d(0, 0, 0.03), 0.0);
  ASSERT_TRUE(ray_hit.has_value());
  EXPECT_EQ(ray_hit->tube, kBile);
  EXPECT_NEAR(ray_hit->s_m, 0.025, 1e-3);
}

TEST(TriangleStructuresTest, ClipsAndCutsRefuseWhatTheInstrumentCannotDo) {
  TriangleStructures s(DefaultTriangleDescription());
  const double l = s.TubeLength_m(kArtery);
  EXPECT_EQ(s.PlaceClip(kArtery, -0.001), ToolActionResult::kOutsideTube);
  EXPECT_EQ(s.PlaceClip(kArtery, l + 0.001), ToolActionResult::kOutsideTube);
  EXPECT_EQ(s.PlaceClip(kArtery, 0.02), ToolActionResult::kDone);
  EXPECT_EQ(s.PlaceClip(kArtery, 0.0205), ToolActionResult::kOnClip);
  EXPECT_EQ(s.Cut(kArtery, 0.0203), ToolActionResult::kOnClip);
  EXPECT_EQ(s.Cut(kArtery, 0.025), ToolActionResult::kDone);
  EXPECT_EQ(s.Cut(kArtery, 0.025), ToolActionResult::kAlreadyCut);
  EXPECT_EQ(s.PlaceClip(kArtery, 0.0252), ToolActionResult::kAlreadyCut);
  EXPECT_THROW(s.PlaceClip(7, 0.01), std::out_of_range);
  EXPECT_THROW(s.ClipPosition(3), std::out_of_range);
}

TEST(TriangleStructuresTest, ABadDescriptionNamesTheTubeAndItsSource) {
  TriangleDescription d = DefaultTriangleDescription();
  d.tubes[kHepatic].centreline_m.resize(1);
  d.tubes[kHepatic].source = "variant.toml:31";
  try {
    TriangleStructures s(d);
    FAIL();
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("common hepatic duct"), std::string::npos) << message;
    EXPECT_NE(message.find("variant.toml:31"), std::string::npos) << message;
    EXPECT_NE(message.find("centreline_m"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace vesica::physics::calot
