#pragma once
// What the BEM precompute of a surface will cost before it starts: the dense blocks it holds at
// its peak (H and G, 3n x 3n each, while the Green's functions Xi, 3n x 3n_free, are filled) and
// an estimate of the time (assembly ~ n^2, dense LU and solve ~ (3n)^3). The trainer refuses a
// surface whose peak would not fit and warns about a long one, instead of running silent for
// minutes and gigabytes.

#include <cstdint>
#include <string>

namespace vesica::physics {

struct BemPrecomputeCost {
  std::uint64_t peak_bytes = 0;  ///< H + G + Xi, 8-byte doubles
  double seconds = 0;            ///< estimate on a 2-core x86-64 machine (see the .cpp's rates)
};

/// Cost for a surface of `num_vertices` vertices of which `num_free` are not fixed.
BemPrecomputeCost EstimateBemPrecomputeCost(std::int64_t num_vertices, std::int64_t num_free);

/// "5008 vertices: about 5.4 GB of memory and 6 min" (decimal units, rounded).
std::string DescribeBemPrecomputeCost(std::int64_t num_vertices, const BemPrecomputeCost& cost);

}  // namespace vesica::physics
