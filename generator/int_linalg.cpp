#include "generator/int_linalg.h"

#include <numeric>

#include "generator/error.h"

namespace boxgen::generator {

std::int64_t det(const IntColumns& a) {
  const size_t n = a.size();
  if (n == 1) return a[0][0];
  if (n == 2) return a[0][0] * a[1][1] - a[1][0] * a[0][1];
  if (n == 3)
    return a[0][0] * (a[1][1] * a[2][2] - a[2][1] * a[1][2]) -
           a[1][0] * (a[0][1] * a[2][2] - a[2][1] * a[0][2]) +
           a[2][0] * (a[0][1] * a[1][2] - a[1][1] * a[0][2]);
  fail_internal("det: only dimensions 1 to 3 are supported");
}

int rank(const IntColumns& columns, int n) {
  // Fraction-free elimination on a copy (rows = coordinates).
  std::vector<std::vector<Rational>> m(n, std::vector<Rational>(columns.size()));
  for (size_t j = 0; j < columns.size(); ++j)
    for (int i = 0; i < n; ++i) m[i][j] = rational_from(columns[j][i]);
  int r = 0;
  for (size_t col = 0; col < columns.size() && r < n; ++col) {
    int pivot = -1;
    for (int i = r; i < n; ++i)
      if (!cln::zerop(m[i][col])) {
        pivot = i;
        break;
      }
    if (pivot < 0) continue;
    std::swap(m[pivot], m[r]);
    for (int i = r + 1; i < n; ++i) {
      if (cln::zerop(m[i][col])) continue;
      Rational f = m[i][col] / m[r][col];
      for (size_t j = col; j < columns.size(); ++j) m[i][j] = m[i][j] - f * m[r][j];
    }
    ++r;
  }
  return r;
}

std::int64_t gcd_of(const IntVec& v) {
  std::int64_t g = 0;
  for (auto x : v) g = std::gcd(g, x < 0 ? -x : x);
  return g;
}

IntVec sign_canonical(IntVec v) {
  for (auto x : v) {
    if (x == 0) continue;
    if (x < 0)
      for (auto& y : v) y = -y;
    break;
  }
  return v;
}

IntVec primitive(IntVec v) {
  std::int64_t g = gcd_of(v);
  if (g == 0) return v;
  for (auto& x : v) x /= g;
  return sign_canonical(std::move(v));
}

std::optional<IntVec> hyperplane_normal(const IntColumns& c, int n) {
  IntVec nu;
  if (n == 2) {
    nu = {-c[0][1], c[0][0]};
  } else if (n == 3) {
    nu = {c[0][1] * c[1][2] - c[0][2] * c[1][1], c[0][2] * c[1][0] - c[0][0] * c[1][2],
          c[0][0] * c[1][1] - c[0][1] * c[1][0]};
  } else {
    fail_internal("hyperplane_normal: only dimensions 2 and 3 are supported");
  }
  if (gcd_of(nu) == 0) return std::nullopt;
  return primitive(nu);
}

RatMatrix inverse(const IntColumns& a) {
  const int n = static_cast<int>(a.size());
  // Augmented Gauss-Jordan on row-major A = [a_ij] with a_ij = a[j][i].
  std::vector<RatVec> m(n, RatVec(2 * static_cast<std::size_t>(n)));
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) m[i][j] = rational_from(a[j][i]);
    for (int j = 0; j < n; ++j) m[i][n + j] = i == j ? 1 : 0;
  }
  for (int col = 0; col < n; ++col) {
    int pivot = -1;
    for (int i = col; i < n; ++i)
      if (!cln::zerop(m[i][col])) {
        pivot = i;
        break;
      }
    if (pivot < 0) fail_internal("inverse of a singular matrix");
    std::swap(m[pivot], m[col]);
    Rational p = m[col][col];
    for (auto& x : m[col]) x = x / p;
    for (int i = 0; i < n; ++i) {
      if (i == col || cln::zerop(m[i][col])) continue;
      Rational f = m[i][col];
      for (int j = 0; j < 2 * n; ++j) m[i][j] = m[i][j] - f * m[col][j];
    }
  }
  RatMatrix inv(n, RatVec(n));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) inv[i][j] = m[i][n + j];
  return inv;
}

std::optional<RatVec> solve(const IntColumns& a, const RatVec& b) {
  if (det(a) == 0) return std::nullopt;
  RatMatrix inv = inverse(a);
  RatVec x(b.size(), 0);
  for (size_t i = 0; i < b.size(); ++i)
    for (size_t j = 0; j < b.size(); ++j) x[i] = x[i] + inv[i][j] * b[j];
  return x;
}

}  // namespace boxgen::generator
