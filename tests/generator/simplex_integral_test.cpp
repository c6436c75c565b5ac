// Exact simplex integrals against the closed form over the standard simplex,
// integral of x^a y^b z^c = a! b! c! / (a + b + c + n)!.
#include "generator/simplex_integral.h"

#include <gtest/gtest.h>

namespace boxgen {
namespace {

Poly monomial(int n, const Exponent& e) {
  Poly p(n, 0);
  p.set_coefficient(e, 1);
  return p;
}

TEST(SimplexIntegral, StandardTriangle) {
  const std::vector<RatVec> t{{0, 0}, {1, 0}, {0, 1}};
  EXPECT_EQ(simplex_volume(t), Rational(1) / 2);
  EXPECT_EQ(integrate_over_simplex(monomial(2, {1, 0, 0}), t), Rational(1) / 6);
  EXPECT_EQ(integrate_over_simplex(monomial(2, {2, 1, 0}), t), Rational(1) / 60);    // 2! 1! / 5!
  EXPECT_EQ(integrate_over_simplex(monomial(2, {4, 3, 0}), t), Rational(1) / 2520);  // 4! 3! / 9!
}

TEST(SimplexIntegral, StandardTetrahedronUpToDegreeSix) {
  const std::vector<RatVec> t{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  EXPECT_EQ(simplex_volume(t), Rational(1) / 6);
  EXPECT_EQ(integrate_over_simplex(monomial(3, {1, 1, 1}), t), Rational(1) / 720);    // 1/6!
  EXPECT_EQ(integrate_over_simplex(monomial(3, {3, 2, 1}), t), Rational(1) / 30240);  // 12 / 9!
}

TEST(SimplexIntegral, AnyVertexOrderAndPlacement) {
  // The triangle (1,1), (3,1), (1,3) is the standard one scaled by 2 and moved by (1,1): area 2,
  // and the integral of x is area times the centroid's x, 2 * 5/3.
  const std::vector<RatVec> t{{3, 1}, {1, 1}, {1, 3}};
  EXPECT_EQ(simplex_volume(t), 2);
  EXPECT_EQ(integrate_over_simplex(monomial(2, {1, 0, 0}), t), Rational(10) / 3);
}

}  // namespace
}  // namespace boxgen
