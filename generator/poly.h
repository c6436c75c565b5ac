// Dense exact polynomials in n = 2 or 3 variables with CLN rational coefficients.
// Monomials are stored in graded order (all of degree 0, then 1, ...), so a polynomial of
// lower degree is a prefix of one of higher degree: growing the capacity only appends zeros.
// This is the hot-loop representation of the generator (docs/design.md §12); GiNaC expressions are
// made from it only at the edges (printing, emission).
#pragma once
#include <array>
#include <vector>

#include "generator/rational.h"

namespace boxgen::generator {

using Exponent = std::array<int, 3>;  // unused trailing entries are 0

// Number of monomials of total degree <= degree in n variables.
std::size_t monomial_count(int n, int degree);
// Position of a monomial in the graded order (independent of any capacity).
std::size_t monomial_index(int n, const Exponent& e);
// Exponents of all monomials of degree <= degree, in graded order.
const std::vector<Exponent>& monomial_exponents(int n, int degree);

class Poly {
 public:
  Poly() = default;
  Poly(int n, int capacity);  // zero polynomial able to hold degree <= capacity
  static Poly constant(int n, const Rational& c);
  // a[0] + a[1] x_1 + ... + a[n] x_n
  static Poly affine(const RatVec& a);

  int vars() const { return n_; }
  int capacity() const { return cap_; }
  int degree() const;  // -1 for the zero polynomial
  bool is_zero() const;
  const std::vector<Rational>& coefficients() const { return c_; }
  const Rational& coefficient(const Exponent& e) const;
  void set_coefficient(const Exponent& e, const Rational& v);

  Poly& operator+=(const Poly& o);
  Poly& operator-=(const Poly& o);
  Poly& operator*=(const Rational& s);
  friend Poly operator+(Poly a, const Poly& b) { return a += b; }
  friend Poly operator-(Poly a, const Poly& b) { return a -= b; }
  friend Poly operator*(Poly a, const Rational& s) { return a *= s; }
  bool operator==(const Poly& o) const;
  bool operator!=(const Poly& o) const { return !(*this == o); }

  Poly operator*(const Poly& o) const;
  // this * (a[0] + sum a[i+1] x_i)
  Poly times_affine(const RatVec& a) const;
  Rational eval(const RatVec& x) const;
  // P(x - s)
  Poly translated(const RatVec& s) const;
  // P(A x + b), A row-major n x n (rows give the new coordinates in terms of x)
  Poly composed_affine(const std::vector<RatVec>& a, const RatVec& b) const;
  Poly derivative(int var) const;
  // P with x_var replaced by the affine form a[0] + sum a[k+1] x_k (a[var+1] must be 0).
  Poly substituted(int var, const RatVec& a) const;
  // Q(x) = P(y) with y_i = sign[i] x_perm[i]: P composed with a signed permutation.
  Poly signed_permuted(const std::vector<int>& perm, const std::vector<int>& sign) const;
  // P(f x): the coefficient of x^e times f^|e| (generator/common_scale.h).
  Poly stretched(const Rational& f) const;
  // Coefficients Q_e with P(x - tau d) = sum_e tau^e Q_e(x).
  std::vector<Poly> along_direction(const IntVec& d) const;
  void reserve_degree(int capacity);
  void trim();  // shrink the capacity to the actual degree

 private:
  int n_ = 0;
  int cap_ = -1;
  std::vector<Rational> c_;
};

}  // namespace boxgen::generator
