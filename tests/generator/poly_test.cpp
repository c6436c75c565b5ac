// Dense exact polynomials: every operation against values expanded by hand.
#include "generator/poly.h"

#include <gtest/gtest.h>

#include <cstdint>

namespace boxgen::generator {
namespace {

// x^2 y + 3 in two variables.
Poly sample() {
  Poly p(2, 3);
  p.set_coefficient({2, 1, 0}, 1);
  p.set_coefficient({0, 0, 0}, 3);
  return p;
}

TEST(Poly, GradedMonomialOrder) {
  EXPECT_EQ(monomial_count(2, 3), 10u);
  EXPECT_EQ(monomial_count(3, 2), 10u);
  EXPECT_EQ(monomial_count(3, -1), 0u);
  EXPECT_EQ(monomial_index(3, {0, 0, 0}), 0u);
  // Degree 1 follows degree 0; within a degree the first exponent descends.
  EXPECT_EQ(monomial_exponents(3, 1)[1], (Exponent{1, 0, 0}));
  EXPECT_EQ(monomial_exponents(3, 1)[3], (Exponent{0, 0, 1}));
  for (std::size_t i = 0; i < monomial_count(3, 4); ++i)
    EXPECT_EQ(monomial_index(3, monomial_exponents(3, 4)[i]), i);
}

TEST(Poly, ArithmeticAndEvaluation) {
  const Poly p = sample();
  EXPECT_EQ(p.degree(), 3);
  EXPECT_EQ(p.eval({3, 5}), 48);  // 9 * 5 + 3
  EXPECT_EQ((p + p).eval({3, 5}), 96);
  EXPECT_TRUE((p - p).is_zero());
  EXPECT_EQ((p * (Rational(1) / 2)).eval({3, 5}), 24);
  // (x + 1)(y - 2) at (2, 3) is 3; times_affine is the same product.
  const Poly a = Poly::affine({1, 1, 0});
  const Poly b = Poly::affine({-2, 0, 1});
  EXPECT_EQ((a * b).eval({2, 3}), 3);
  EXPECT_EQ(a.times_affine({-2, 0, 1}), a * b);
  EXPECT_EQ(Poly::constant(2, 7).eval({100, -100}), 7);
}

TEST(Poly, TranslationDerivativeAndSubstitution) {
  const Poly p = sample();
  // translated(s)(x) = p(x - s): at (4, 7) with s = (1, 2) it is p(3, 5).
  EXPECT_EQ(p.translated({1, 2}).eval({4, 7}), 48);
  EXPECT_EQ(p.derivative(0).eval({3, 5}), 30);  // 2 x y
  EXPECT_EQ(p.derivative(1).eval({3, 5}), 9);   // x^2
  // y replaced by 2x + 1: x^2 (2x + 1) + 3, at x = 2: 23.
  EXPECT_EQ(p.substituted(1, {1, 2, 0}).eval({2, 0}), 23);
  // p(A x + b) with A = [[0, 1], [1, 0]] (swap) and b = (1, 0): (y + 1)^2 x + 3 at (2, 3): 35.
  EXPECT_EQ(p.composed_affine({{0, 1}, {1, 0}}, {1, 0}).eval({2, 3}), 35);
  // Signed permutation y_0 = -x_1, y_1 = x_0: p(-x_1, x_0) = x_1^2 x_0 + 3, at (2, 3): 21.
  EXPECT_EQ(p.signed_permuted({1, 0}, {-1, 1}).eval({2, 3}), 21);
}

TEST(Poly, AlongADirection) {
  // p(x - t d) for p = x^2 y and d = (1, 0): (x - t)^2 y = x^2 y - 2 t x y + t^2 y.
  Poly p(2, 3);
  p.set_coefficient({2, 1, 0}, 1);
  const std::vector<Poly> q = p.along_direction({1, 0});
  ASSERT_GE(q.size(), 3u);
  EXPECT_EQ(q[0], p);
  EXPECT_EQ(q[1].eval({3, 5}), -30);
  EXPECT_EQ(q[2].eval({3, 5}), 5);
  for (std::size_t e = 3; e < q.size(); ++e) EXPECT_TRUE(q[e].is_zero());
}

TEST(Poly, EqualityIgnoresCapacityAndTrimShrinksIt) {
  Poly wide(2, 6);
  wide.set_coefficient({1, 0, 0}, 2);
  Poly narrow(2, 1);
  narrow.set_coefficient({1, 0, 0}, 2);
  EXPECT_EQ(wide, narrow);
  wide.trim();
  EXPECT_EQ(wide.capacity(), 1);
  EXPECT_EQ(Poly(3, 2).degree(), -1);
}

// Translation runs in integers over one denominator (poly.cpp); it must equal P(x - s) exactly
// for rational coefficients and shifts of any denominators: checked against the composition
// P(I x - s) (another routine) and against values on the principal lattice of degree d, which
// determines a polynomial of degree <= d.
TEST(Poly, TranslationWithDenominatorsMatchesCompositionAndValues) {
  std::uint32_t seed = 1;  // unsigned: the generator wraps modulo 2^32 by design
  auto next = [&seed] {
    seed = seed * 1103515245u + 12345u;
    return static_cast<int>(seed >> 1);
  };
  for (int n : {2, 3})
    for (int d : {0, 1, 2, 5, 9}) {
      Poly p(n, d);
      for (const auto& e :
           std::vector<Exponent>(monomial_exponents(n, d).begin(),
                                 monomial_exponents(n, d).begin() +
                                     static_cast<std::ptrdiff_t>(monomial_count(n, d))))
        if (next() % 4 != 0)
          p.set_coefficient(e, Rational(next() % 41 - 20) / Rational(1 + next() % 12));
      const std::vector<RatVec> shifts{
          RatVec(n, Rational(0)), RatVec(n, Rational(3)), RatVec(n, Rational(-1) / 2),
          n == 2 ? RatVec{Rational(1) / 3, Rational(-5) / 7}
                 : RatVec{Rational(1) / 3, Rational(-5) / 7, Rational(2)}};
      for (const RatVec& s : shifts) {
        const Poly t = p.translated(s);
        std::vector<RatVec> identity(n, RatVec(n, Rational(0)));
        RatVec minus_s(n);
        for (int k = 0; k < n; ++k) {
          identity[k][k] = 1;
          minus_s[k] = -s[k];
        }
        EXPECT_EQ(t, p.composed_affine(identity, minus_s)) << n << " " << d;
        EXPECT_LE(t.degree(), d);
        for (std::size_t i = 0; i < monomial_count(n, d); ++i) {
          const Exponent& e = monomial_exponents(n, d)[i];
          RatVec x(n), x_minus_s(n);
          for (int k = 0; k < n; ++k) {
            x[k] = Rational(e[k]) + Rational(1) / 5;
            x_minus_s[k] = x[k] - s[k];
          }
          ASSERT_EQ(t.eval(x), p.eval(x_minus_s)) << n << " " << d;
        }
      }
    }
}

}  // namespace
}  // namespace boxgen::generator
