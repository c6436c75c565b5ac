// Exact sums of many polynomials over one common denominator (docs/design.md §12).
//
// Adding CLN rationals costs a gcd per coefficient. The partition-of-unity check adds a whole
// stencil (hundreds of polynomials) on every region, and most terms recur from region to region.
// Here each distinct term is converted once to integer numerators over a denominator D shared by
// all terms (the lcm of their coefficients' denominators); a sum is then integer additions, and
// sum / D is exactly the rational sum.
#pragma once
#include <vector>

#include "generator/poly.h"

namespace boxgen::generator {

// The lcm of the denominators of every coefficient of every polynomial (1 if there are none).
Integer common_denominator(const std::vector<const Poly*>& polys);

// d * p as integer numerators in p's graded monomial order; InternalError unless d clears every
// denominator of p.
std::vector<Integer> scaled_numerators(const Poly& p, const Integer& d);

// A polynomial as integer numerators over one denominator of its own (the lcm of its
// coefficients' denominators), kept for repeated sums.
struct ScaledPoly {
  int vars = 0;
  int capacity = 0;
  Integer denominator = 1;
  std::vector<Integer> numerators;  // graded monomial order
  bool is_zero() const;
};
ScaledPoly scaled(const Poly& p);

// The exact sum of the terms: each term's numerators are brought to the lcm of the terms'
// denominators by one factor per term, so the work per coefficient is an integer product and
// sum, not a rational sum with its gcd.
Poly sum_scaled(int n, const std::vector<const ScaledPoly*>& terms);

// Terms of one common denominator, each added to sums by its index.
class CommonDenominatorTerms {
 public:
  // All terms the sums will use, in n variables.
  CommonDenominatorTerms(int n, const std::vector<const Poly*>& terms);

  const Integer& denominator() const { return d_; }
  std::size_t size() const { return numerators_.size(); }
  // The exact sum of the terms with these indices (repeats count), as a rational polynomial.
  Poly sum(const std::vector<int>& indices) const;
  // True if that sum equals the constant c (cheaper than building the sum's Poly).
  bool sum_is_constant(const std::vector<int>& indices, const Rational& c) const;

 private:
  std::vector<Integer> integer_sum(const std::vector<int>& indices) const;

  int n_;
  int capacity_ = 0;
  Integer d_;
  std::vector<std::vector<Integer>> numerators_;
};

}  // namespace boxgen::generator
