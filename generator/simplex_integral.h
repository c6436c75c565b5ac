// Exact integrals of polynomials over simplices by the Grundmann-Moeller rule: rational points
// and weights, exact for every polynomial of degree <= 2s+1 (Grundmann & Moeller, SIAM J. Numer.
// Anal. 15, 1978). Cheaper than composing the polynomial with the simplex's affine map, and run
// in integers: the polynomial over one denominator, each simplex's vertices over another.
#pragma once
#include <vector>

#include "generator/poly.h"

namespace boxgen::generator {

// Integrals of one polynomial over many simplices (its integer form made once).
class SimplexIntegrator {
 public:
  explicit SimplexIntegrator(const Poly& p);
  // The integral over the simplex with these n+1 vertices.
  Rational over(const std::vector<RatVec>& vertices) const;

 private:
  int n_, degree_;
  Integer denominator_;              // D
  std::vector<Integer> numerators_;  // N_e of the nonzero monomials
  std::vector<Exponent> exponents_;
};

// Integral of p over the simplex with the given n+1 vertices.
Rational integrate_over_simplex(const Poly& p, const std::vector<RatVec>& vertices);
// Volume of a simplex.
Rational simplex_volume(const std::vector<RatVec>& vertices);

}  // namespace boxgen::generator
