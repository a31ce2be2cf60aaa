#include "physics/needle/capsule_force.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace vesica::physics {

double Equation14::Force_N(double depth_m) const {
  return (nu_N + phi_N) * std::exp(tau_per_m * (depth_m - omega_m)) + phi_N;  // eq. 14
}

CapsuleForceParameters FittedCapsuleForceParameters() {
  // Three targets per piece, solved exactly for (nu, phi) with tau and omega chosen:
  // before: F(0) = 0 and F(omega) = peak, so (nu + phi)(1 - e^(-tau omega)) = peak;
  // after: F(omega) = level and F'(omega) = tau (nu + phi) = slope.
  constexpr double kPeak_N = 2.0, kDepth_m = 0.010, kTauBefore = 300.0;
  constexpr double kLevel_N = 0.6, kSlope_N_per_m = 12.0, kTauAfter = 30.0;
  CapsuleForceParameters p;
  const double a = kPeak_N / (1.0 - std::exp(-kTauBefore * kDepth_m));  // nu + phi
  p.before = {kTauBefore, kDepth_m, a - (kPeak_N - a), kPeak_N - a};
  const double b = kSlope_N_per_m / kTauAfter;  // nu + phi
  p.after = {kTauAfter, kDepth_m, b - (kLevel_N - b), kLevel_N - b};
  p.puncture_depth_m = kDepth_m;
  return p;
}

void ValidateCapsuleForceParameters(const CapsuleForceParameters& p) {
  const auto check = [](const Equation14& e, const char* which) {
    if (!std::isfinite(e.tau_per_m) || !std::isfinite(e.omega_m) || !std::isfinite(e.nu_N) || !std::isfinite(e.phi_N))
      throw std::invalid_argument(std::string("capsule force: eq. 14 parameters '") + which + "' must be finite");
  };
  check(p.before, "before");
  check(p.after, "after");
  if (!(p.puncture_depth_m > 0.0 && std::isfinite(p.puncture_depth_m)))
    throw std::invalid_argument("capsule force: puncture_depth_m must be > 0");
}

double CapsuleForce_N(const CapsuleForceParameters& p, double depth_m, bool punctured) {
  if (depth_m <= 0.0) return 0.0;
  if (!punctured) return p.before.Force_N(depth_m);
  if (depth_m >= p.puncture_depth_m) return p.after.Force_N(depth_m);
  // Withdrawn (or breathed) back above the puncture depth: eq. 14 was measured advancing; here
  // the force falls linearly to 0 at the capsule, so leaving the liver is felt without a jump.
  return p.after.Force_N(p.puncture_depth_m) * depth_m / p.puncture_depth_m;
}

}  // namespace vesica::physics
