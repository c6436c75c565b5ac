#include "analysis/quadrature.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace boxgen::analysis {

namespace {

double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// Sorted breakpoints with near-duplicates merged.
std::vector<double> unique_sorted(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  std::vector<double> out;
  for (double x : v)
    if (out.empty() || x - out.back() > 1e-12 * (1 + std::abs(x))) out.push_back(x);
  return out;
}

// The slice of the cell with the first `fixed` coordinates set: constraints on the remaining
// coordinates, written as half-spaces of R^(n - fixed) (the fixed part moved to the offset).
std::vector<HalfSpace> slice(const VoronoiCell& cell, const Vec& w, int fixed) {
  std::vector<HalfSpace> out;
  for (const auto& h : cell.faces) {
    HalfSpace s{{0, 0, 0}, h.offset};
    for (int i = 0; i < fixed && i < 3; ++i) s.offset -= h.normal[i] * w[i];
    for (int i = fixed; i < cell.n && i < 3; ++i) s.normal[i - fixed] = h.normal[i];
    out.push_back(s);
  }
  return out;
}

// Integrates over coordinate `level` (0-based) with the earlier coordinates fixed in w.
double iterate(const VoronoiCell& cell, const Integrand& f, const GaussRule& g, Vec w, int level) {
  const int remaining = cell.n - level;
  if (level < 0 || level > 2 || remaining < 1) return 0;  // n <= 3 (also tells GCC the bounds)
  const std::vector<HalfSpace> cons = slice(cell, w, level);
  std::vector<double> breaks;
  if (remaining == 1) {
    double lo = -1e300, hi = 1e300;
    for (const auto& h : cons) {
      const double a = h.normal[0];
      if (std::abs(a) < 1e-14) continue;
      if (a > 0)
        hi = std::min(hi, h.offset / a);
      else
        lo = std::max(lo, h.offset / a);
    }
    if (!(hi > lo)) return 0;
    breaks = {lo, hi};
  } else {
    for (const auto& v : polytope_vertices(cons, remaining, 1e-11)) breaks.push_back(v[0]);
    breaks = unique_sorted(breaks);
    if (breaks.size() < 2) return 0;
  }
  double sum = 0;
  for (std::size_t p = 0; p + 1 < breaks.size(); ++p) {
    const double a = breaks[p], len = breaks[p + 1] - breaks[p];
    for (std::size_t k = 0; k < g.nodes.size(); ++k) {
      w[level] = a + len * g.nodes[k];
      const double inner = remaining == 1 ? f(w) : iterate(cell, f, g, w, level + 1);
      sum += len * g.weights[k] * inner;
    }
  }
  return sum;
}

}  // namespace

GaussRule gauss_legendre(int order) {
  if (order < 1 || order > 1000)
    throw std::invalid_argument("Gauss-Legendre order must be 1..1000");
  GaussRule r;
  r.nodes.resize(order);
  r.weights.resize(order);
  // Newton on the Legendre polynomial from the Tricomi initial guesses, on [-1, 1].
  for (int i = 0; i < order; ++i) {
    long double x = std::cos(std::numbers::pi_v<long double> * (i + 0.75L) / (order + 0.5L));
    long double dp = 0;
    for (int it = 0; it < 100; ++it) {
      long double p0 = 1, p1 = x;
      for (int k = 2; k <= order; ++k) {
        const long double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      if (order == 1) p0 = 1;
      dp = order * (x * p1 - p0) / (x * x - 1);
      const long double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-19L) break;
    }
    long double p0 = 1, p1 = x;
    for (int k = 2; k <= order; ++k) {
      const long double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
      p0 = p1;
      p1 = p2;
    }
    if (order == 1) p0 = 1;
    dp = order * (x * p1 - p0) / (x * x - 1);
    const long double weight = 2 / ((1 - x * x) * dp * dp);
    r.nodes[i] = static_cast<double>((1 + x) / 2);
    r.weights[i] = static_cast<double>(weight / 2);
  }
  return r;
}

double integrate_simplex_fan(const VoronoiCell& cell, const Integrand& f, int order) {
  const GaussRule g = gauss_legendre(order);
  double sum = 0;
  for (const auto& face : cell.face_vertices) {
    if (cell.n == 2) {
      // Triangle (0, a, b): w = s1 a + s1 s2 (b - a), Jacobian |det(a, b)| s1.
      const Vec& a = cell.vertices[face[0]];
      const Vec& b = cell.vertices[face[1]];
      const double det = std::abs(a[0] * b[1] - a[1] * b[0]);
      const Vec ba = sub(b, a);
      for (std::size_t i = 0; i < g.nodes.size(); ++i)
        for (std::size_t j = 0; j < g.nodes.size(); ++j) {
          const double s1 = g.nodes[i], s2 = g.nodes[j];
          const Vec w{s1 * (a[0] + s2 * ba[0]), s1 * (a[1] + s2 * ba[1]), 0};
          sum += g.weights[i] * g.weights[j] * det * s1 * f(w);
        }
      continue;
    }
    for (std::size_t t = 1; t + 1 < face.size(); ++t) {
      // Tetrahedron (0, a, b, c): w = s1 (a + s2 (b - a + s3 (c - b))), Jacobian |det| s1^2 s2.
      const Vec& a = cell.vertices[face[0]];
      const Vec& b = cell.vertices[face[t]];
      const Vec& c = cell.vertices[face[t + 1]];
      const double det = std::abs(dot(a, cross(b, c)));
      const Vec ba = sub(b, a), cb = sub(c, b);
      for (std::size_t i = 0; i < g.nodes.size(); ++i)
        for (std::size_t j = 0; j < g.nodes.size(); ++j)
          for (std::size_t k = 0; k < g.nodes.size(); ++k) {
            const double s1 = g.nodes[i], s2 = g.nodes[j], s3 = g.nodes[k];
            Vec w;
            for (int r = 0; r < 3; ++r) w[r] = s1 * (a[r] + s2 * (ba[r] + s3 * cb[r]));
            sum += g.weights[i] * g.weights[j] * g.weights[k] * det * s1 * s1 * s2 * f(w);
          }
    }
  }
  return sum;
}

double integrate_iterated(const VoronoiCell& cell, const Integrand& f, int order) {
  const GaussRule g = gauss_legendre(order);
  return iterate(cell, f, g, Vec{0, 0, 0}, 0);
}

}  // namespace boxgen::analysis
