#pragma once
// The extreme eigenvalues of a preconditioned operator P^-1 A, estimated from the coefficients a
// conjugate-gradient solve computed anyway: CG is the Lanczos process in disguise, and its step
// lengths alpha_j and direction weights beta_j give the Lanczos tridiagonal T (Saad, "Iterative
// Methods for Sparse Linear Systems", 2nd ed., §6.7.3). T's eigenvalues (the Ritz values) lie inside
// P^-1 A's spectrum, and its extreme ones converge to the spectrum's ends first. They say what sets
// an iteration count: CG gains about log10((sqrt(k) + 1) / (sqrt(k) - 1)) decades an iteration on
// a spectrum [l, l k] without outliers.

#include <span>

namespace vesica::physics {

struct SpectrumEstimate {
  double smallest = 0.0;  ///< smallest Ritz value (>= the smallest eigenvalue of P^-1 A)
  double largest = 0.0;   ///< largest Ritz value (<= the largest eigenvalue)
  /// largest / smallest: a lower bound on P^-1 A's condition number; 0 without an iteration.
  double condition() const { return smallest > 0.0 ? largest / smallest : 0.0; }
};

/// From CG's alpha_0..alpha_{m-1} and beta_0..beta_{m-2} (beta_j = r_{j+1}.z_{j+1} / r_j.z_j, the
/// weight of the old direction in the next): T(j, j) = 1 / alpha_j + beta_{j-1} / alpha_{j-1},
/// T(j, j+1) = sqrt(beta_j) / alpha_j. `betas` may hold one more entry than needed (ignored).
/// Empty `alphas`: {0, 0}.
SpectrumEstimate EstimateSpectrumFromCg(std::span<const double> alphas, std::span<const double> betas);

}  // namespace vesica::physics
