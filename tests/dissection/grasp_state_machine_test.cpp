#include "physics/grasp/grasp_state_machine.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace vesica::physics {
namespace {

using State = GraspStateMachine::State;

SurfaceHit Touch(int triangle) {
  SurfaceHit h;
  h.surface = 1;
  h.triangle = triangle;
  h.weights = {0.2, 0.3, 0.5};
  return h;
}

GraspInput Jaw(double angle) {
  GraspInput in;
  in.jaw_angle = angle;
  return in;
}

GraspInput Open() { return Jaw(0.5); }

GraspInput CloseOn(std::vector<SurfaceHit> hits) {
  GraspInput in = Jaw(0.0);
  in.hits = std::move(hits);
  return in;
}

// Holding input: the jaw at the origin, each grasped point at the given offset and force.
GraspInput Hold(std::vector<Eigen::Vector3d> positions, std::vector<double> forces) {
  GraspInput in = Jaw(0.0);
  in.grasped_positions = std::move(positions);
  in.constraint_forces = std::move(forces);
  return in;
}

TEST(GraspStateMachineTest, ClosingWhileTouchingGraspsTheTouchedElements) {
  GraspStateMachine g;
  EXPECT_EQ(g.state(), State::kOpen);
  const auto e = g.Update(CloseOn({Touch(7), Touch(9)}));
  EXPECT_TRUE(e.grasped);
  EXPECT_EQ(g.state(), State::kHolding);
  ASSERT_EQ(g.points().size(), 2u);
  EXPECT_EQ(g.points()[0].triangle, 7);
  EXPECT_EQ(g.points()[1].surface, 1);
  EXPECT_TRUE(g.points()[1].weights.isApprox(Eigen::Vector3d(0.2, 0.3, 0.5)));
}

TEST(GraspStateMachineTest, ClosingInAirGraspsNothingUntilReopened) {
  GraspStateMachine g;
  EXPECT_FALSE(g.Update(CloseOn({})).grasped);
  EXPECT_EQ(g.state(), State::kClosedEmpty);
  EXPECT_FALSE(g.Update(CloseOn({Touch(1)})).grasped);  // touching with a shut jaw
  EXPECT_EQ(g.state(), State::kClosedEmpty);
  g.Update(Jaw(0.1));  // between the thresholds: still shut (hysteresis)
  EXPECT_EQ(g.state(), State::kClosedEmpty);
  g.Update(Open());
  EXPECT_EQ(g.state(), State::kOpen);
  EXPECT_TRUE(g.Update(CloseOn({Touch(1)})).grasped);
}

TEST(GraspStateMachineTest, OpenJawTouchingDoesNotGrasp) {
  GraspStateMachine g;
  GraspInput in = Open();
  in.hits = {Touch(2)};
  EXPECT_FALSE(g.Update(in).grasped);
  EXPECT_EQ(g.state(), State::kOpen);
}

TEST(GraspStateMachineTest, OpeningReleases) {
  GraspStateMachine g;
  g.Update(CloseOn({Touch(3)}));
  const auto e = g.Update(Open());
  EXPECT_TRUE(e.released);
  EXPECT_EQ(g.state(), State::kOpen);
  EXPECT_TRUE(g.points().empty());
  EXPECT_EQ(g.total_slips(), 0);
}

TEST(GraspStateMachineTest, HoldsWithinSlipDistanceAndSlipsBeyondIt) {
  GraspStateMachine g;  // slip distance 10 mm
  g.Update(CloseOn({Touch(3), Touch(4)}));
  auto e = g.Update(Hold({{0.0099, 0, 0}, {0, 0.0099, 0}}, {1.0, 1.0}));
  EXPECT_EQ(e.slipped, 0);
  EXPECT_EQ(g.points().size(), 2u);
  e = g.Update(Hold({{0.0101, 0, 0}, {0, 0.005, 0}}, {1.0, 1.0}));
  EXPECT_EQ(e.slipped, 1);
  ASSERT_EQ(g.points().size(), 1u);
  EXPECT_EQ(g.points()[0].triangle, 4);
  EXPECT_EQ(g.state(), State::kHolding);
  EXPECT_EQ(g.total_slips(), 1);
}

TEST(GraspStateMachineTest, SlipsWhenForceExceedsFrictionLimit) {
  GraspStateMachine g({.friction_limit = 2.0});
  g.Update(CloseOn({Touch(3)}));
  EXPECT_EQ(g.Update(Hold({{0, 0, 0}}, {2.0})).slipped, 0);  // at the limit: holds
  const auto e = g.Update(Hold({{0, 0, 0}}, {2.01}));
  EXPECT_EQ(e.slipped, 1);
  EXPECT_EQ(g.state(), State::kClosedEmpty);  // nothing left: must reopen to grasp again
  EXPECT_EQ(g.total_slips(), 1);
  g.Update(Open());
  g.Update(CloseOn({Touch(5)}));
  g.Update(Hold({{0.02, 0, 0}}, {0.0}));
  EXPECT_EQ(g.total_slips(), 2);  // slips accumulate over grasps
}

TEST(GraspStateMachineTest, RejectsBadInput) {
  EXPECT_THROW(GraspStateMachine({.close_angle = 0.2, .open_angle = 0.1}), std::invalid_argument);
  EXPECT_THROW(GraspStateMachine({.slip_distance = 0.0}), std::invalid_argument);
  EXPECT_THROW(GraspStateMachine({.friction_limit = -1.0}), std::invalid_argument);
  GraspStateMachine g;
  EXPECT_THROW(g.Update(Jaw(NAN)), std::invalid_argument);
  g.Update(CloseOn({Touch(3)}));
  EXPECT_THROW(g.Update(Hold({}, {})), std::invalid_argument);
  EXPECT_EQ(g.state(), State::kHolding);  // rejected input changes nothing
}

}  // namespace
}  // namespace vesica::physics
