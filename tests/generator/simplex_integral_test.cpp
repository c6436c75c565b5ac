// Exact simplex integrals against the closed form over the standard simplex,
// integral of x^a y^b z^c = a! b! c! / (a + b + c + n)!.
#include "generator/simplex_integral.h"

#include <gtest/gtest.h>

namespace boxgen::generator {
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

// The integer form (one denominator for the polynomial, one for the vertices) against the
// definition: q(t) = p(v0 + A t) over the standard simplex, term by term with the closed form,
// times |det A|. Rational vertices and coefficients, degree 4 (rule with s = 2), and the same
// integrator reused on a second simplex.
TEST(SimplexIntegral, RationalTetrahedraAgainstTheAffineSubstitution) {
  Poly p(3, 4);
  p.set_coefficient({0, 0, 0}, Rational(7) / 3);
  p.set_coefficient({1, 0, 0}, Rational(-2) / 5);
  p.set_coefficient({0, 2, 1}, Rational(11) / 4);
  p.set_coefficient({2, 1, 1}, Rational(-3) / 7);
  p.set_coefficient({0, 0, 4}, Rational(5) / 6);
  const SimplexIntegrator integrate(p);
  const std::vector<std::vector<RatVec>> simplices{
      {{Rational(1) / 3, 0, Rational(-1) / 2},
       {2, Rational(1) / 5, 0},
       {0, 1, Rational(2) / 3},
       {Rational(1) / 4, Rational(3) / 4, 2}},
      {{-1, -1, -1}, {Rational(5) / 2, 0, 1}, {0, Rational(7) / 3, 0}, {1, 1, Rational(9) / 4}}};
  for (const auto& v : simplices) {
    std::vector<RatVec> rows(3, RatVec(3));  // x_i = v0_i + sum_k (v_{k+1} - v0)_i t_k
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) rows[i][k] = v[k + 1][i] - v[0][i];
    const Poly q = p.composed_affine(rows, v[0]);
    Rational standard = 0;
    for (const auto& e : monomial_exponents(3, q.capacity())) {
      const Rational& c = q.coefficient(e);
      if (cln::zerop(c)) continue;
      // integral of t^e over the standard simplex: e0! e1! e2! / (|e| + 3)!
      Integer num = 1, den = 1;
      for (int k : e)
        for (int f = 2; f <= k; ++f) num = num * f;
      for (int f = 2; f <= e[0] + e[1] + e[2] + 3; ++f) den = den * f;
      standard = standard + c * Rational(num) / Rational(den);
    }
    const Rational det = rows[0][0] * (rows[1][1] * rows[2][2] - rows[2][1] * rows[1][2]) -
                         rows[1][0] * (rows[0][1] * rows[2][2] - rows[2][1] * rows[0][2]) +
                         rows[2][0] * (rows[0][1] * rows[1][2] - rows[1][1] * rows[0][2]);
    EXPECT_EQ(integrate.over(v), standard * cln::abs(det));
    EXPECT_EQ(integrate_over_simplex(p, v), standard * cln::abs(det));
  }
}

}  // namespace
}  // namespace boxgen::generator
