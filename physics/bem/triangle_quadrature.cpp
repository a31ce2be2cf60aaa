#include "physics/bem/triangle_quadrature.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace vesica::physics {

std::vector<std::array<double, 2>> GaussLegendreUnitInterval(int order) {
  if (order < 1) throw std::invalid_argument("GaussLegendreUnitInterval: order must be >= 1");
  std::vector<std::array<double, 2>> rule(static_cast<std::size_t>(order));
  for (int i = 0; i < order; ++i) {
    // Newton on the Legendre polynomial P_order from the Chebyshev-like initial guess.
    double x = std::cos(std::numbers::pi * (i + 0.75) / (order + 0.5));
    double derivative = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= order; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      derivative = order * (x * p1 - p0) / (x * x - 1.0);
      const double step = p1 / derivative;
      x -= step;
      if (std::abs(step) < 1e-15) break;
    }
    const double weight = 2.0 / ((1.0 - x * x) * derivative * derivative);
    rule[static_cast<std::size_t>(i)] = {0.5 * (1.0 - x), 0.5 * weight};
  }
  return rule;
}

const TriangleQuadrature& TriangleGauss3() {
  static const TriangleQuadrature rule{{{2.0 / 3, 1.0 / 6, 1.0 / 6}, 1.0 / 3},
                                       {{1.0 / 6, 2.0 / 3, 1.0 / 6}, 1.0 / 3},
                                       {{1.0 / 6, 1.0 / 6, 2.0 / 3}, 1.0 / 3}};
  return rule;
}

const TriangleQuadrature& TriangleGauss7() {
  static const TriangleQuadrature rule = [] {
    constexpr double a1 = 0.059715871789770, b1 = 0.470142064105115, w1 = 0.132394152788506;
    constexpr double a2 = 0.797426985353087, b2 = 0.101286507323456, w2 = 0.125939180544827;
    return TriangleQuadrature{{{1.0 / 3, 1.0 / 3, 1.0 / 3}, 0.225},
                              {{a1, b1, b1}, w1},
                              {{b1, a1, b1}, w1},
                              {{b1, b1, a1}, w1},
                              {{a2, b2, b2}, w2},
                              {{b2, a2, b2}, w2},
                              {{b2, b2, a2}, w2}};
  }();
  return rule;
}

TriangleQuadrature TriangleDuffy(int singular_corner, int order) {
  if (singular_corner < 0 || singular_corner > 2)
    throw std::invalid_argument("TriangleDuffy: singular_corner must be 0, 1 or 2");
  const auto line = GaussLegendreUnitInterval(order);
  TriangleQuadrature rule;
  rule.reserve(line.size() * line.size());
  const int next = (singular_corner + 1) % 3, last = (singular_corner + 2) % 3;
  for (const auto& [u, wu] : line)
    for (const auto& [v, wv] : line) {
      // x = P_s + u (P_next - P_s) + u v (P_last - P_next); dA = 2 area u du dv.
      TriangleQuadraturePoint point{};
      point.barycentric[static_cast<std::size_t>(singular_corner)] = 1.0 - u;
      point.barycentric[static_cast<std::size_t>(next)] = u * (1.0 - v);
      point.barycentric[static_cast<std::size_t>(last)] = u * v;
      point.weight = 2.0 * u * wu * wv;
      rule.push_back(point);
    }
  return rule;
}

}  // namespace vesica::physics
