// Exact integrals of polynomials over simplices by the Grundmann-Moeller rule: rational points
// and weights, exact for every polynomial of degree <= 2s+1 (Grundmann & Moeller, SIAM J. Numer.
// Anal. 15, 1978). Cheaper than composing the polynomial with the simplex's affine map.
#pragma once
#include <vector>

#include "generator/poly.h"

namespace boxgen {

// Integral of p over the simplex with the given n+1 vertices.
Rational integrate_over_simplex(const Poly& p, const std::vector<RatVec>& vertices);
// Volume of a simplex.
Rational simplex_volume(const std::vector<RatVec>& vertices);

}  // namespace boxgen
