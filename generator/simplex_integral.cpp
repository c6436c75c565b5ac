#include "generator/simplex_integral.h"

#include <map>
#include <mutex>

#include "generator/error.h"

namespace boxgen::generator {

namespace {

struct Rule {
  // Point q has barycentric coordinates (2 beta_j + 1) / denominator (beta_j >= 0 integers).
  std::vector<std::vector<int>> beta;
  std::vector<int> denominator;
  std::vector<Rational> weights;  // relative to the unit simplex, sum = 1/n!
};

Integer factorial(int k) {
  Integer f = 1;
  for (int i = 2; i <= k; ++i) f = f * i;
  return f;
}

void compositions(int total, int parts, std::vector<int>& cur, std::vector<std::vector<int>>& out) {
  if (parts == 1) {
    cur.push_back(total);
    out.push_back(cur);
    cur.pop_back();
    return;
  }
  for (int v = 0; v <= total; ++v) {
    cur.push_back(v);
    compositions(total - v, parts - 1, cur, out);
    cur.pop_back();
  }
}

const Rule& rule(int n, int s) {
  static std::mutex mutex;
  static std::map<std::pair<int, int>, Rule> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto key = std::make_pair(n, s);
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  Rule r;
  const int d = 2 * s + 1;
  for (int i = 0; i <= s; ++i) {
    const int denom = d + n - 2 * i;
    Rational w =
        cln::expt(Rational(denom), d) / (Rational(factorial(i)) * Rational(factorial(d + n - i)));
    w = w / cln::expt(Rational(2), 2 * s);
    if (i % 2) w = -w;
    std::vector<std::vector<int>> betas;
    std::vector<int> cur;
    compositions(s - i, n + 1, cur, betas);
    for (const auto& b : betas) {
      r.beta.push_back(b);
      r.denominator.push_back(denom);
      r.weights.push_back(w);
    }
  }
  return cache.emplace(key, std::move(r)).first->second;
}

}  // namespace

Rational simplex_volume(const std::vector<RatVec>& v) {
  const size_t n = v[0].size();
  std::vector<RatVec> m(n, RatVec(n));
  for (size_t i = 0; i < n; ++i)
    for (size_t k = 0; k < n; ++k) m[i][k] = v[i + 1][k] - v[0][k];
  // 2-D and 3-D by cofactors (no divisions: this runs for every simplex of every integral).
  if (n == 2) return cln::abs(m[0][0] * m[1][1] - m[0][1] * m[1][0]) / Rational(2);
  if (n == 3)
    return cln::abs(m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                    m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                    m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])) /
           Rational(6);
  Rational d = 1;
  for (size_t col = 0; col < n; ++col) {
    size_t pivot = col;
    while (pivot < n && cln::zerop(m[pivot][col])) ++pivot;
    if (pivot == n) return 0;
    if (pivot != col) std::swap(m[pivot], m[col]), d = -d;
    d = d * m[col][col];
    for (size_t i = col + 1; i < n; ++i) {
      Rational f = m[i][col] / m[col][col];
      for (size_t k = col; k < n; ++k) m[i][k] = m[i][k] - f * m[col][k];
    }
  }
  return cln::abs(d) / Rational(factorial(static_cast<int>(n)));
}

SimplexIntegrator::SimplexIntegrator(const Poly& p)
    : n_(p.vars()), degree_(std::max(p.degree(), 0)) {
  // p = sum_e N_e x^e / D with integers N_e: every point's value is then an integer sum.
  const auto& c = p.coefficients();
  const std::size_t count = p.degree() < 0 ? 0 : monomial_count(n_, degree_);
  denominator_ = 1;
  for (std::size_t i = 0; i < count; ++i)
    denominator_ = cln::lcm(denominator_, cln::denominator(c[i]));
  const auto& exponents = monomial_exponents(n_, degree_);
  for (std::size_t i = 0; i < count; ++i) {
    if (cln::zerop(c[i])) continue;
    numerators_.push_back(cln::numerator(c[i]) * cln::exquo(denominator_, cln::denominator(c[i])));
    exponents_.push_back(exponents[i]);
  }
}

Rational SimplexIntegrator::over(const std::vector<RatVec>& vertices) const {
  if (numerators_.empty()) return 0;
  const Rule& r = rule(n_, degree_ / 2);  // exact up to degree 2s+1 >= degree
  const std::size_t n = static_cast<std::size_t>(n_);
  // Vertices as integers over one denominator: v_j = V_j / w.
  Integer w = 1;
  for (const auto& v : vertices)
    for (const auto& x : v) w = cln::lcm(w, cln::denominator(x));
  std::vector<std::vector<Integer>> big(vertices.size(), std::vector<Integer>(n));
  std::vector<Integer> sum(n, 0);
  for (std::size_t j = 0; j < vertices.size(); ++j)
    for (std::size_t k = 0; k < n; ++k) {
      big[j][k] = cln::numerator(vertices[j][k]) * cln::exquo(w, cln::denominator(vertices[j][k]));
      sum[k] = sum[k] + big[j][k];
    }
  // Point q: x = sum_j (2 beta_j + 1) / m * V_j / w = (S + 2 sum_j beta_j V_j) / (m w), with
  // S = sum_j V_j. p(Y / t) = sum_e N_e Y^e t^(d - |e|) / (D t^d), all integers but the last.
  Rational total = 0;
  std::vector<std::vector<Integer>> powers(n, std::vector<Integer>(degree_ + 1));
  std::vector<Integer> t_powers(degree_ + 1);
  for (std::size_t q = 0; q < r.weights.size(); ++q) {
    std::vector<Integer> y = sum;
    for (std::size_t j = 0; j < vertices.size(); ++j)
      if (const int b = r.beta[q][j]; b != 0)
        for (std::size_t k = 0; k < n; ++k) y[k] = y[k] + 2 * b * big[j][k];
    const Integer t = r.denominator[q] * w;
    t_powers[0] = 1;
    for (int e = 1; e <= degree_; ++e) t_powers[e] = t_powers[e - 1] * t;
    for (std::size_t k = 0; k < n; ++k) {
      powers[k][0] = 1;
      for (int e = 1; e <= degree_; ++e) powers[k][e] = powers[k][e - 1] * y[k];
    }
    Integer value = 0;
    for (std::size_t i = 0; i < numerators_.size(); ++i) {
      Integer term = numerators_[i];
      int order = 0;
      for (std::size_t k = 0; k < n; ++k) {
        const int e = exponents_[i][k];
        if (e) term = term * powers[k][e];
        order += e;
      }
      value = value + term * t_powers[degree_ - order];
    }
    total = total + r.weights[q] * Rational(value) / Rational(t_powers[degree_]);
  }
  // The rule integrates over the unit simplex (volume 1/n!); n! vol = |det(V_j - V_0)| / w^n.
  std::vector<RatVec> integral_vertices(vertices.size(), RatVec(n));
  for (std::size_t j = 0; j < vertices.size(); ++j)
    for (std::size_t k = 0; k < n; ++k) integral_vertices[j][k] = Rational(big[j][k]);
  return total * simplex_volume(integral_vertices) * Rational(factorial(n_)) /
         (Rational(denominator_) * cln::expt(Rational(w), n_));
}

Rational integrate_over_simplex(const Poly& p, const std::vector<RatVec>& vertices) {
  return SimplexIntegrator(p).over(vertices);
}

}  // namespace boxgen::generator
