#pragma once
// Internal to cholmod_solver.cpp: a supernodal Cholesky factor stored as IEEE half (binary16)
// times a power-of-two scale, solved in float. The preconditioner solve of kRotatedFactorPcg is
// memory bound (it streams the whole factor twice); half the bytes of the float copy. Needs
// F16C (with AVX2 and FMA), compiled for it in half_factor_f16c.cpp and chosen at run time.

#include <cstddef>
#include <cstdint>

namespace vesica::physics {

/// Supernode s holds columns [super[s], super[s+1]) as a dense column-major block of
/// pi[s+1] - pi[s] rows (row indices rows[pi[s]...], the first ones its own columns) starting at
/// values[px[s]] (the layout of CHOLMOD's supernodal factor).
struct HalfFactorView {
  const int* super = nullptr;
  const int* pi = nullptr;
  const int* px = nullptr;
  const int* rows = nullptr;
  int num_supernodes = 0;
  const std::uint16_t* values = nullptr;  ///< followed by 8 readable entries (zeros)
};

/// True when this CPU runs the F16C kernels.
bool HalfFactorSupported();
/// out[k] = half(scale * x[k]); call only when HalfFactorSupported().
void ConvertToHalfF16c(const double* x, std::size_t n, double scale, std::uint16_t* out);
/// y <- (L L^T)^-1 y in the factor's permuted order, L the stored (scaled) factor; `gathered`
/// holds at least the widest supernode's below-diagonal row count. Only when HalfFactorSupported().
void HalfFactorSolveF16c(const HalfFactorView& factor, float* y, float* gathered);

}  // namespace vesica::physics
