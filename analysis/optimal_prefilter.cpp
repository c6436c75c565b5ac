#include "analysis/optimal_prefilter.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "analysis/quadrature.h"

namespace boxgen::analysis {

namespace {

using Point = std::vector<std::int64_t>;
using Matrix = std::vector<std::vector<long double>>;

// G(g, h) = |det G| sum_{j in g, k in h} a(j - k) between orbits (a is zero off its table).
Matrix gram(const DualLattice& dual, const std::vector<LatticeTap>& autocorrelation,
            const std::vector<std::vector<Point>>& orbits) {
  std::map<Point, double> a;
  for (const auto& t : autocorrelation) a[t.point] = t.value;
  const std::size_t m = orbits.size();
  Matrix g(m, std::vector<long double>(m, 0));
  for (std::size_t r = 0; r < m; ++r)
    for (std::size_t c = 0; c < m; ++c)
      for (const Point& j : orbits[r])
        for (const Point& k : orbits[c]) {
          Point d = j;
          for (std::size_t i = 0; i < d.size(); ++i) d[i] -= k[i];
          if (auto it = a.find(d); it != a.end()) g[r][c] += dual.det_g() * it->second;
        }
  return g;
}

// (1/|N|) ∫_N psi_hat(w) sum_{j in orbit} cos(w.j) dw by the iterated rule of `order`.
double projection(const BoxSplineSpectrum& psi, const DualLattice& dual,
                  const std::vector<Point>& orbit, int order) {
  const Integrand f = [&](const Vec& w) {
    double c = 0;
    for (const Point& j : orbit) {
      double t = 0;
      for (std::size_t i = 0; i < j.size(); ++i) t += w[i] * static_cast<double>(j[i]);
      c += std::cos(t);
    }
    return psi(w) * c;
  };
  const double volume = std::pow(2 * std::numbers::pi, dual.dimension()) / dual.det_g();
  return integrate_iterated(dual.cell(), f, order) / volume;
}

// Solves h x = r by Gaussian elimination with partial pivoting; throws if h is singular.
std::vector<long double> solve(Matrix h, std::vector<long double> r) {
  const std::size_t m = r.size();
  for (std::size_t c = 0; c < m; ++c) {
    std::size_t best = c;
    for (std::size_t i = c + 1; i < m; ++i)
      if (std::fabs(h[i][c]) > std::fabs(h[best][c])) best = i;
    if (h[best][c] == 0)
      throw std::invalid_argument("the integrated error kernel does not depend on a parameter");
    std::swap(h[best], h[c]);
    std::swap(r[best], r[c]);
    for (std::size_t i = c + 1; i < m; ++i) {
      const long double f = h[i][c] / h[c][c];
      for (std::size_t k = c; k < m; ++k) h[i][k] -= f * h[c][k];
      r[i] -= f * r[c];
    }
  }
  std::vector<long double> x(m, 0);
  for (std::size_t c = m; c-- > 0;) {
    long double s = r[c];
    for (std::size_t k = c + 1; k < m; ++k) s -= h[c][k] * x[k];
    x[c] = s / h[c][c];
  }
  return x;
}

long double objective(const Matrix& g, const std::vector<long double>& b,
                      const std::vector<long double>& q) {
  long double v = 1;
  for (std::size_t r = 0; r < q.size(); ++r) {
    v -= 2 * b[r] * q[r];
    for (std::size_t c = 0; c < q.size(); ++c) v += q[r] * g[r][c] * q[c];
  }
  return v;
}

}  // namespace

OptimisedParameters minimise_integrated_error(const BoxSplineSpectrum& psi, const DualLattice& dual,
                                              const std::vector<LatticeTap>& autocorrelation,
                                              const PrefilterFamilyValues& family,
                                              const std::vector<int>& orders) {
  const std::size_t m = family.orbits.size();
  if (m == 0 || family.particular.size() != m || orders.size() < 2)
    throw std::invalid_argument("the optimisation needs a family of prefilters and two orders");
  const Matrix g = gram(dual, autocorrelation, family.orbits);
  std::vector<long double> b(m), q0(m);
  OptimisedParameters out;
  for (std::size_t o = 0; o < m; ++o) {
    const double coarse = projection(psi, dual, family.orbits[o], orders[orders.size() - 2]);
    const double fine = projection(psi, dual, family.orbits[o], orders.back());
    b[o] = fine;
    out.quadrature_change = std::max(out.quadrature_change, std::fabs(fine - coarse));
    q0[o] = family.particular[o];
  }
  out.at_zero = static_cast<double>(objective(g, b, q0));

  // q = q0 + B t: minimise t^T (B^T G B) t - 2 t^T B^T (b - G q0).
  const std::size_t p = family.basis.size();
  Matrix h(p, std::vector<long double>(p, 0));
  std::vector<long double> r(p, 0), residual = b;
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t k = 0; k < m; ++k) residual[i] -= g[i][k] * q0[k];
  for (std::size_t s = 0; s < p; ++s) {
    for (std::size_t i = 0; i < m; ++i) {
      r[s] += family.basis[s][i] * residual[i];
      for (std::size_t u = 0; u < p; ++u)
        for (std::size_t k = 0; k < m; ++k)
          h[s][u] += family.basis[s][i] * g[i][k] * family.basis[u][k];
    }
  }
  const std::vector<long double> t = p == 0 ? std::vector<long double>{} : solve(h, r);
  std::vector<long double> q = q0;
  for (std::size_t s = 0; s < p; ++s) {
    out.parameters.push_back(static_cast<double>(t[s]));
    for (std::size_t i = 0; i < m; ++i) q[i] += out.parameters.back() * family.basis[s][i];
  }
  out.optimised = static_cast<double>(objective(g, b, q));
  return out;
}

}  // namespace boxgen::analysis
