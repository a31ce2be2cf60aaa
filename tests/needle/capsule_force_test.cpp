// Eq. 14 of the biopsy paper (the liver capsule's force) and its fitted parameters: the shape of the
// seed's Figure 11 (zero at first touch, a peak at puncture, a sharp drop, rising resistance).
#include "physics/needle/capsule_force.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace vesica::physics {
namespace {

TEST(CapsuleForceTest, Equation14AsPrinted) {
  const Equation14 e{50.0, 0.004, 1.5, 0.25};
  for (double d : {0.0, 0.002, 0.004, 0.011})
    EXPECT_NEAR(e.Force_N(d), (1.5 + 0.25) * std::exp(50.0 * (d - 0.004)) + 0.25, 1e-15);
}

TEST(CapsuleForceTest, FittedParametersAreTheDocumentedOnes) {
  const CapsuleForceParameters p = FittedCapsuleForceParameters();
  // docs/needle.md: before tau 300 /m, omega 10 mm, nu + phi = 2 / (1 - e^-3), phi = 2 - (nu + phi).
  const double a = 2.0 / (1.0 - std::exp(-3.0));
  EXPECT_DOUBLE_EQ(p.before.tau_per_m, 300.0);
  EXPECT_DOUBLE_EQ(p.before.omega_m, 0.010);
  EXPECT_NEAR(p.before.phi_N, 2.0 - a, 1e-15);
  EXPECT_NEAR(p.before.nu_N, a - (2.0 - a), 1e-15);
  EXPECT_NEAR(p.before.nu_N, 2.2096, 1e-4);
  EXPECT_NEAR(p.before.phi_N, -0.1048, 1e-4);
  EXPECT_DOUBLE_EQ(p.after.tau_per_m, 30.0);
  EXPECT_DOUBLE_EQ(p.after.omega_m, 0.010);
  EXPECT_NEAR(p.after.nu_N, 0.2, 1e-15);
  EXPECT_NEAR(p.after.phi_N, 0.2, 1e-15);
  EXPECT_DOUBLE_EQ(p.puncture_depth_m, 0.010);
}

TEST(CapsuleForceTest, FigureElevenShape) {
  const CapsuleForceParameters p = FittedCapsuleForceParameters();
  EXPECT_NEAR(CapsuleForce_N(p, 0.0, false), 0.0, 1e-15);    // first touch: no jump
  EXPECT_EQ(CapsuleForce_N(p, -0.001, false), 0.0);          // not yet touching
  EXPECT_NEAR(CapsuleForce_N(p, 0.010, false), 2.0, 1e-12);  // the peak at puncture
  double previous = 0.0;
  for (double d = 0.0005; d < 0.010; d += 0.0005) {  // rising, ever faster (exponential)
    const double f = CapsuleForce_N(p, d, false);
    EXPECT_GT(f, previous);
    previous = f;
  }
  EXPECT_NEAR(CapsuleForce_N(p, 0.010, true), 0.6, 1e-12);  // the sharp drop
  const double slope = (CapsuleForce_N(p, 0.010 + 1e-7, true) - CapsuleForce_N(p, 0.010, true)) / 1e-7;
  EXPECT_NEAR(slope, 12.0, 1e-4);  // forward difference: eq. 14's slope there, 12 N/m
  EXPECT_GT(CapsuleForce_N(p, 0.040, true), CapsuleForce_N(p, 0.020, true));  // rising resistance
  // Drawn back above the puncture depth: down to 0 at the capsule, linearly.
  EXPECT_NEAR(CapsuleForce_N(p, 0.005, true), 0.3, 1e-12);
  EXPECT_EQ(CapsuleForce_N(p, 0.0, true), 0.0);
  EXPECT_EQ(CapsuleForce_N(p, -0.001, true), 0.0);
}

TEST(CapsuleForceTest, BadParametersAreRefusedByName) {
  CapsuleForceParameters p = FittedCapsuleForceParameters();
  p.before.tau_per_m = NAN;
  EXPECT_THROW(ValidateCapsuleForceParameters(p), std::invalid_argument);
  p = FittedCapsuleForceParameters();
  p.puncture_depth_m = 0.0;
  try {
    ValidateCapsuleForceParameters(p);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("puncture_depth_m"), std::string::npos);
  }
}

}  // namespace
}  // namespace vesica::physics
