#include "generator/simplex_integral.h"

#include <map>
#include <mutex>

#include "generator/error.h"

namespace boxgen {

namespace {

struct Rule {
  std::vector<RatVec> barycentric;  // n+1 coordinates each
  std::vector<Rational> weights;    // relative to the unit simplex, sum = 1/n!
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
      RatVec bary;
      for (int v : b) bary.push_back(Rational(2 * v + 1) / Rational(denom));
      r.barycentric.push_back(bary);
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

Rational integrate_over_simplex(const Poly& p, const std::vector<RatVec>& vertices) {
  const int n = p.vars();
  const int deg = std::max(p.degree(), 0);
  const Rule& r = rule(n, deg / 2);  // exact up to degree 2s+1 >= deg
  Rational sum = 0;
  for (size_t q = 0; q < r.weights.size(); ++q) {
    RatVec x(n, Rational(0));
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k < n; ++k) x[k] = x[k] + r.barycentric[q][j] * vertices[j][k];
    sum = sum + r.weights[q] * p.eval(x);
  }
  // The rule integrates over the unit simplex (volume 1/n!); rescale to this simplex.
  return sum * simplex_volume(vertices) * Rational(factorial(n));
}

}  // namespace boxgen
