// The 1-D cardinal B-spline by its explicit truncated-power sum: an independent reference for
// tensor-product box splines in the tests.
#pragma once
#include "generator/rational.h"

namespace boxgen::generator::fixture {

inline Rational power(const Rational& b, int e) {
  Rational r = 1;
  for (int i = 0; i < e; ++i) r = r * b;
  return r;
}

// B_k(x) = 1/(k-1)! sum_i (-1)^i C(k,i) (x-i)_+^(k-1), order k (degree k-1, knots 0..k).
inline Rational cardinal_bspline(int k, const Rational& x) {
  Rational sum = 0, binom = 1, factorial = 1;
  for (int i = 1; i < k; ++i) factorial = factorial * i;
  for (int i = 0; i <= k; ++i) {
    const Rational y = x - i;
    if (y > 0) sum = sum + (i % 2 == 0 ? binom : Rational(-binom)) * power(y, k - 1);
    binom = binom * (k - i) / (i + 1);
  }
  return sum / factorial;
}

}  // namespace boxgen::generator::fixture
