#include "generator/bbform.h"

#include "generator/error.h"

namespace boxgen::generator {

namespace {

Integer factorial(int k) {
  Integer f = 1;
  for (int i = 2; i <= k; ++i) f = f * i;
  return f;
}

void fill(int parts, int total, MultiIndex& cur, std::vector<MultiIndex>& out) {
  if (parts == 1) {
    cur.push_back(total);
    out.push_back(cur);
    cur.pop_back();
    return;
  }
  for (int v = total; v >= 0; --v) {
    cur.push_back(v);
    fill(parts - 1, total - v, cur, out);
    cur.pop_back();
  }
}

// Row-major n x n matrix of edge vectors v_i - v_0 as columns, and v_0.
std::pair<std::vector<RatVec>, RatVec> simplex_frame(const std::vector<RatVec>& s) {
  const size_t n = s[0].size();
  std::vector<RatVec> a(n, RatVec(n));
  for (size_t k = 0; k < n; ++k)
    for (size_t i = 0; i < n; ++i) a[k][i] = s[i + 1][k] - s[0][k];
  return {a, s[0]};
}

}  // namespace

std::vector<MultiIndex> bb_multi_indices(int n, int d) {
  std::vector<MultiIndex> out;
  MultiIndex cur;
  fill(n + 1, d, cur, out);
  return out;
}

std::vector<Rational> bb_coefficients(const Poly& p, const std::vector<RatVec>& simplex, int d) {
  const int n = p.vars();
  auto [a, v0] = simplex_frame(simplex);
  // q(lambda_1..lambda_n) = p(v0 + sum lambda_i (v_i - v0))
  const Poly q = p.composed_affine(a, v0);
  const auto& ex = monomial_exponents(n, std::max(q.capacity(), 0));
  std::vector<Rational> out;
  const Rational dfact = Rational(factorial(d));
  for (const auto& b : bb_multi_indices(n, d)) {
    // c_b = sum_{a <= b} q_a (d - |a|)!/d! prod_i b_i!/(b_i - a_i)!
    Rational c = 0;
    for (std::size_t m = 0; m < q.coefficients().size(); ++m) {
      if (cln::zerop(q.coefficients()[m])) continue;
      int total = 0;
      bool fits = true;
      Rational f = 1;
      for (int i = 0; i < n; ++i) {
        const int ai = ex[m][i], bi = b[i + 1];
        if (ai > bi) fits = false;
        total += ai;
        if (fits) f = f * Rational(factorial(bi)) / Rational(factorial(bi - ai));
      }
      if (!fits || total > d) continue;
      c = c + q.coefficients()[m] * f * Rational(factorial(d - total)) / dfact;
    }
    out.push_back(c);
  }
  return out;
}

std::vector<RatVec> barycentric_forms(const std::vector<RatVec>& simplex) {
  const int n = static_cast<int>(simplex[0].size());
  auto [a, v0] = simplex_frame(simplex);
  // lambda(x) = A^{-1}(x - v0), lambda_0 = 1 - sum lambda_i
  std::vector<RatVec> aug(n, RatVec(2 * static_cast<std::size_t>(n)));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      aug[i][j] = a[i][j];
      aug[i][n + j] = i == j ? 1 : 0;
    }
  for (int col = 0; col < n; ++col) {
    int piv = col;
    while (piv < n && cln::zerop(aug[piv][col])) ++piv;
    if (piv == n) fail_internal("degenerate simplex");
    std::swap(aug[piv], aug[col]);
    const Rational pv = aug[col][col];
    for (auto& x : aug[col]) x = x / pv;
    for (int i = 0; i < n; ++i) {
      if (i == col || cln::zerop(aug[i][col])) continue;
      const Rational f = aug[i][col];
      for (int j = 0; j < 2 * n; ++j) aug[i][j] = aug[i][j] - f * aug[col][j];
    }
  }
  std::vector<RatVec> lambda(n + 1, RatVec(n + 1, Rational(0)));  // affine forms a0 + a.x
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const Rational inv = aug[i][n + j];
      lambda[i + 1][j + 1] = inv;
      lambda[i + 1][0] = lambda[i + 1][0] - inv * v0[j];
    }
  }
  lambda[0][0] = 1;
  for (int i = 1; i <= n; ++i)
    for (int k = 0; k <= n; ++k) lambda[0][k] = lambda[0][k] - lambda[i][k];
  return lambda;
}

Poly bb_polynomial(const std::vector<Rational>& coefficients, const std::vector<RatVec>& simplex,
                   int d) {
  const int n = static_cast<int>(simplex[0].size());
  const std::vector<RatVec> lambda = barycentric_forms(simplex);
  Poly out(n, d);
  const auto indices = bb_multi_indices(n, d);
  for (size_t t = 0; t < indices.size(); ++t) {
    if (cln::zerop(coefficients[t])) continue;
    Poly term = Poly::constant(n, 1);
    Integer denom = 1;
    for (int i = 0; i <= n; ++i) {
      for (int e = 0; e < indices[t][i]; ++e) term = term.times_affine(lambda[i]);
      denom = denom * factorial(indices[t][i]);
    }
    out += term * (coefficients[t] * Rational(factorial(d)) / Rational(denom));
  }
  out.trim();
  return out;
}

RegionBBForm region_bb_form(const ReferenceRegion& region, int degree) {
  RegionBBForm out;
  out.degree = degree;
  out.stencil = region.stencil;
  const int n = static_cast<int>(region.vertices[0].size());
  std::vector<std::vector<RatVec>> simplices;
  if (static_cast<int>(region.vertices.size()) == n + 1) {
    simplices.push_back(region.vertices);
  } else {
    out.triangulated = true;
    simplices = triangulate_polytope(region.vertices, region.planes);
  }
  for (const auto& s : simplices) {
    SimplexBBForm f;
    f.vertices = s;
    f.indices = bb_multi_indices(n, degree);
    f.weights.assign(f.indices.size(), std::vector<Rational>(region.basis.size()));
    for (size_t k = 0; k < region.basis.size(); ++k) {
      const auto c = bb_coefficients(region.basis[k], s, degree);
      for (size_t b = 0; b < c.size(); ++b) f.weights[b][k] = c[b];
    }
    out.simplices.push_back(std::move(f));
  }
  return out;
}

}  // namespace boxgen::generator
