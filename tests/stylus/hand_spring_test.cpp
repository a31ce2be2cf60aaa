#include "app/omnisim/hand_spring.h"

#include <gtest/gtest.h>

#include <cmath>

namespace vesica::app {
namespace {

// At rest the device's force is balanced by the grip: p = target + F / k.
TEST(HandSpringTest, SettlesAtTargetPlusForceOverStiffness) {
  HandSpringParameters params;
  HandSpring hand(params, Eigen::Vector3d::Zero());
  const Eigen::Vector3d target(0.01, -0.02, 0.005);
  const Eigen::Vector3d force(0.0, 1.5, -3.0);
  for (int i = 0; i < 2000; ++i) hand.Step(0.001, target, force);
  const Eigen::Vector3d expected = target + force / params.stiffness_N_per_m;
  EXPECT_LT((hand.position_m() - expected).norm(), 1e-9);
  EXPECT_LT(hand.velocity_m_per_s().norm(), 1e-7);
}

// Critically damped: it never overshoots the target on the way there.
TEST(HandSpringTest, CriticallyDampedDoesNotOvershoot) {
  HandSpring hand({}, Eigen::Vector3d::Zero());
  double largest = 0.0;
  for (int i = 0; i < 1000; ++i) {
    hand.Step(0.001, {0.01, 0.0, 0.0}, Eigen::Vector3d::Zero());
    largest = std::max(largest, hand.position_m().x());
  }
  EXPECT_LE(largest, 0.01 * (1.0 + 1e-6));
  EXPECT_NEAR(hand.position_m().x(), 0.01, 1e-8);
}

TEST(HandSpringTest, BadParametersAreRefused) {
  HandSpringParameters p;
  p.mass_kg = 0.0;
  EXPECT_THROW(HandSpring(p, Eigen::Vector3d::Zero()), std::invalid_argument);
  p = {};
  p.stiffness_N_per_m = -1.0;
  EXPECT_THROW(HandSpring(p, Eigen::Vector3d::Zero()), std::invalid_argument);
  p = {};
  p.damping_ratio = std::nan("");
  EXPECT_THROW(HandSpring(p, Eigen::Vector3d::Zero()), std::invalid_argument);
  EXPECT_DOUBLE_EQ(HandSpringParameters{}.damping_N_s_per_m(), 2.0 * std::sqrt(300.0 * 0.05));
}

}  // namespace
}  // namespace vesica::app
