// The least-squares fits of the calibration on exact data (analytic answers) and on data that
// cannot be fitted.
#include <gtest/gtest.h>

#include <cmath>

#include "device/calibration/friction_fit.h"
#include "device/calibration/gravity_fit.h"

namespace vesica::device::calibration {
namespace {

TEST(FrictionFitTest, ExactSweepsGiveCoulombViscousAndOffset) {
  std::vector<FrictionSegment> s;
  for (double v : {0.3, 0.6, 1.2, -0.3, -0.6, -1.2})
    s.push_back({v, 0.008 * (v > 0 ? 1 : -1) + 0.004 * v + 0.02});  // offset: pitch's mean gravity
  const FrictionFit fit = FitFriction(s);
  ASSERT_TRUE(fit.ok);
  EXPECT_NEAR(fit.coulomb, 0.008, 1e-12);
  EXPECT_NEAR(fit.viscous, 0.004, 1e-12);
  EXPECT_NEAR(fit.offset, 0.02, 1e-12);
  EXPECT_NEAR(fit.rms, 0.0, 1e-12);
}

TEST(FrictionFitTest, OneDirectionOnlyCannotTellCoulombFromTheOffset) {
  EXPECT_FALSE(FitFriction({{0.3, 0.01}, {0.6, 0.012}, {1.2, 0.015}}).ok);
  EXPECT_FALSE(FitFriction({{0.3, 0.01}, {-0.3, -0.01}}).ok);  // and two points are too few
  EXPECT_FALSE(FitFriction({}).ok);
}

TEST(GravityFitTest, HoldsOnASineGiveItsTwoComponents) {
  std::vector<GravityHold> holds;
  for (double a : {-0.9, -0.4, 0.0, 0.5, 0.95}) {
    const double hold = -0.04 * std::sin(a) + 0.006 * std::cos(a);
    holds.push_back({a, hold + 0.01, hold - 0.01});  // static friction +-0.01 either way
  }
  const GravityFit fit = FitGravity(holds);
  ASSERT_TRUE(fit.ok);
  EXPECT_NEAR(fit.sin, -0.04, 1e-12);
  EXPECT_NEAR(fit.cos, 0.006, 1e-12);
  EXPECT_FALSE(FitGravity({holds[0]}).ok);
}

}  // namespace
}  // namespace vesica::device::calibration
