#pragma once
// The liver capsule's resistance to the needle (seed 5.3, eq. 14, after Maurin et al. 2004):
//   F_n(d) = (nu + phi) exp(tau (d - omega)) + phi,
// d the tip's depth past the capsule's undeformed surface, along the needle. Piecewise: one set
// of (tau, omega, nu, phi) while the capsule deforms ahead of the tip (d < puncture depth), one
// after it is perforated. The defaults reproduce the shape of the seed's Figure 11: zero at first
// touch, an exponential rise to the peak at puncture, a sharp drop, then a slowly rising
// resistance. docs/needle.md gives the fit.

namespace vesica::physics {

struct Equation14 {
  double tau_per_m = 0.0;  ///< growth rate, 1/m
  double omega_m = 0.0;    ///< depth shift, m
  double nu_N = 0.0;       ///< N
  double phi_N = 0.0;      ///< N
  [[nodiscard]] double Force_N(double depth_m) const;
};

struct CapsuleForceParameters {
  Equation14 before;                ///< while the capsule deforms ahead of the tip
  Equation14 after;                 ///< once perforated
  double puncture_depth_m = 0.010;  ///< the capsule gives way at this depth (> 0), m
};
/// The fitted defaults (docs/needle.md): before: tau 300 /m, omega 10 mm, nu 2.2096 N, phi -0.1048 N
/// (exactly: nu + phi = 2 / (1 - e^-3), phi = 2 - (nu + phi)); after: tau 30 /m, omega 10 mm,
/// nu 0.2 N, phi 0.2 N.
[[nodiscard]] CapsuleForceParameters FittedCapsuleForceParameters();
/// Throws std::invalid_argument naming the field (finite values, puncture depth > 0).
void ValidateCapsuleForceParameters(const CapsuleForceParameters& p);

/// The capsule's force at depth d (m): 0 for d <= 0; before puncture eq. 14 with `before`;
/// punctured, eq. 14 with `after` from the puncture depth on, and below it (the needle drawn back,
/// or the liver breathing up along it) a line from 0 at d = 0 to F_after(puncture depth), so that
/// leaving the liver does not jump.
[[nodiscard]] double CapsuleForce_N(const CapsuleForceParameters& p, double depth_m, bool punctured);

}  // namespace vesica::physics
