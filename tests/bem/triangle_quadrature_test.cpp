#include "physics/bem/triangle_quadrature.h"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>

namespace vesica::physics {
namespace {

// Exact integral of l1^a l2^b over the unit right triangle (area 1/2), divided by the area:
// 2 a! b! / (a + b + 2)!.
double MonomialMean(int a, int b) {
  return 2.0 * std::tgamma(a + 1) * std::tgamma(b + 1) / std::tgamma(a + b + 3);
}

double ApplyRule(const TriangleQuadrature& rule, int a, int b) {
  double sum = 0;
  for (const auto& q : rule) sum += q.weight * std::pow(q.barycentric[1], a) * std::pow(q.barycentric[2], b);
  return sum;
}

TEST(TriangleQuadratureTest, DunavantRulesAreExactToTheirDegree) {
  for (int a = 0; a <= 5; ++a)
    for (int b = 0; a + b <= 5; ++b) {
      EXPECT_NEAR(ApplyRule(TriangleGauss7(), a, b), MonomialMean(a, b), 1e-14) << a << " " << b;
      if (a + b <= 2) {
        EXPECT_NEAR(ApplyRule(TriangleGauss3(), a, b), MonomialMean(a, b), 1e-15);
      }
    }
}

TEST(TriangleQuadratureTest, GaussLegendreIntegratesPolynomialsOnUnitInterval) {
  for (int order : {1, 3, 6}) {
    const auto rule = GaussLegendreUnitInterval(order);
    for (int p = 0; p < 2 * order; ++p) {
      double sum = 0;
      for (const auto& [x, w] : rule) sum += w * std::pow(x, p);
      EXPECT_NEAR(sum, 1.0 / (p + 1), 1e-14) << "order " << order << " degree " << p;
    }
  }
}

// int_T 1/r dA from the right-angle vertex of the unit right triangle = sqrt(2) ln(1 + sqrt(2)).
TEST(TriangleQuadratureTest, DuffyRuleIntegratesOneOverRFromACorner) {
  const double exact = std::sqrt(2.0) * std::log(1.0 + std::sqrt(2.0));
  for (int corner = 0; corner < 3; ++corner)
    for (const auto& [order, tolerance] : {std::pair{8, 1e-6}, std::pair{16, 1e-12}}) {
    double sum = 0;
    for (const auto& q : TriangleDuffy(corner, order)) {
      // Right angle at the singular corner: the other two corners at (1,0) and (0,1).
      const double x = q.barycentric[(corner + 1) % 3], y = q.barycentric[(corner + 2) % 3];
      sum += q.weight * 0.5 / std::hypot(x, y);
    }
    EXPECT_NEAR(sum, exact, tolerance) << "corner " << corner << " order " << order;
  }
}

}  // namespace
}  // namespace vesica::physics
