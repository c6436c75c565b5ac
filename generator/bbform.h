// Bernstein-Bezier form (docs/design.md §6): on a simplex v0..vn a degree-d polynomial is
// sum_{|b|=d} c_b d!/b! lambda^b in barycentric coordinates lambda. For the spline on a region
// each c_b is a linear combination of the stencil values V(j) (the paper's supplemental Table 1
// for M7). Non-simplicial regions are triangulated.
#pragma once
#include <vector>

#include "generator/spline_regions.h"

namespace boxgen::generator {

using MultiIndex = std::vector<int>;  // b_0..b_n, |b| = d

// All multi-indices of n+1 parts summing to d, b_0 descending first (lexicographically largest
// first).
std::vector<MultiIndex> bb_multi_indices(int n, int d);
// Exact BB coefficients of p (degree <= d) on the simplex, in bb_multi_indices order.
std::vector<Rational> bb_coefficients(const Poly& p, const std::vector<RatVec>& simplex, int d);
// The barycentric coordinates of the simplex as exact affine forms of x: lambda_i(x) =
// f[i][0] + sum_j f[i][j + 1] x_j, i = 0..n (they sum to 1 and lambda_i(v_k) = [i == k]).
std::vector<RatVec> barycentric_forms(const std::vector<RatVec>& simplex);
// The polynomial with these BB coefficients (the inverse of bb_coefficients).
Poly bb_polynomial(const std::vector<Rational>& coefficients, const std::vector<RatVec>& simplex,
                   int d);

struct SimplexBBForm {
  std::vector<RatVec> vertices;  // centred frame
  std::vector<MultiIndex> indices;
  std::vector<std::vector<Rational>>
      weights;  // weights[b][k]: c_b = sum_k weights[b][k] V(stencil[k])
};

struct RegionBBForm {
  int degree = 0;
  bool triangulated = false;  // the region is not a simplex; `simplices` triangulate it
  std::vector<IntVec> stencil;
  std::vector<SimplexBBForm> simplices;
};

RegionBBForm region_bb_form(const ReferenceRegion& region, int degree);

}  // namespace boxgen::generator
