#include "support/lattice_regulariser.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>

#include "support/fourier_sums.h"

namespace boxgen::support {

namespace {

using Vec3 = std::array<std::int64_t, 3>;

std::int64_t det3(const std::array<Vec3, 3>& c) {  // the columns c[0], c[1], c[2]
  return c[0][0] * (c[1][1] * c[2][2] - c[1][2] * c[2][1]) -
         c[1][0] * (c[0][1] * c[2][2] - c[0][2] * c[2][1]) +
         c[2][0] * (c[0][1] * c[1][2] - c[0][2] * c[1][1]);
}

// Membership in G Z^n by Cramer's rule on G embedded in 3 x 3 (identity beyond n): x is a
// lattice point when every coordinate det(G with column i replaced by x) / det G is an integer.
class Membership {
 public:
  explicit Membership(const std::vector<std::vector<std::int64_t>>& basis) {
    const std::size_t n = basis.size();
    if (n == 0 || n > 3)
      throw std::invalid_argument("the regulariser takes lattices of dimension 1 to 3");
    for (std::size_t i = 0; i < 3; ++i) {
      columns_[i] = {0, 0, 0};
      if (i < n) {
        if (basis[i].size() != n)
          throw std::invalid_argument("the regulariser's basis must be square");
        for (std::size_t r = 0; r < n; ++r) columns_[i][r] = basis[i][r];
      } else {
        columns_[i][i] = 1;
      }
    }
    det_ = det3(columns_);
    if (det_ == 0) throw std::invalid_argument("the regulariser's lattice basis is singular");
    period_ = 1;
    while (!(contains({period_, 0, 0}) && contains({0, period_, 0}) && contains({0, 0, period_})))
      ++period_;
  }
  std::int64_t period() const { return period_; }
  std::int64_t index() const { return det_ < 0 ? -det_ : det_; }  // |det G|
  bool contains(const Vec3& x) const {
    for (std::size_t i = 0; i < 3; ++i) {
      std::array<Vec3, 3> c = columns_;
      c[i] = x;
      if (det3(c) % det_ != 0) return false;
    }
    return true;
  }

 private:
  std::array<Vec3, 3> columns_{};
  std::int64_t det_ = 1;
  std::int64_t period_ = 1;  // d
};

std::int64_t norm2(const Vec3& x) { return x[0] * x[0] + x[1] * x[1] + x[2] * x[2]; }

// The greatest common divisor of the n x n minors of `steps` (their first n coordinates): the
// index in Z^n of the lattice they generate (0 when they span less than R^n).
std::int64_t minors_gcd(const std::vector<Vec3>& steps, std::size_t n) {
  std::int64_t g = 0;
  const std::size_t m = steps.size();
  auto fold = [&](std::int64_t v) { g = std::gcd(g, v < 0 ? -v : v); };
  for (std::size_t i = 0; i < m; ++i) {
    if (n == 1) {
      fold(steps[i][0]);
      continue;
    }
    for (std::size_t j = i + 1; j < m; ++j) {
      if (n == 2) {
        fold(steps[i][0] * steps[j][1] - steps[i][1] * steps[j][0]);
        continue;
      }
      for (std::size_t k = j + 1; k < m; ++k) fold(det3({steps[i], steps[j], steps[k]}));
    }
  }
  return g;
}

}  // namespace

SymbolBounds symbol_bounds(const LatticeTaps& values) {
  constexpr int kGrid = 64;
  // The values as one kernel on their box of Z^3 (zero off the lattice): A on the grid.
  BoxKernel kernel;
  std::array<int, 3> lo{0, 0, 0}, hi{0, 0, 0};
  for (const auto& [v, w] : values)
    for (std::size_t a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], v[a]);
      hi[a] = std::max(hi[a], v[a]);
    }
  kernel.lo = lo;
  for (std::size_t a = 0; a < 3; ++a) kernel.width[a] = hi[a] - lo[a] + 1;
  kernel.values.assign(static_cast<std::size_t>(kernel.width[0]) *
                           static_cast<std::size_t>(kernel.width[1]) *
                           static_cast<std::size_t>(kernel.width[2]),
                       0.0);
  for (const auto& [v, w] : values) kernel.at(v[0], v[1], v[2]) += w;
  const std::vector<BoxKernel> kernels{kernel};
  FourierSums sums(kernels, {kGrid, kGrid, kGrid}, {kGrid, kGrid, kGrid});
  SymbolBounds b{std::numeric_limits<double>::infinity(), 0};
  for (int k2 = 0; k2 < kGrid; ++k2) {
    sums.set_k2(k2);
    for (int k1 = 0; k1 < kGrid; ++k1) {
      sums.set_k1(k1);
      for (int k0 = 0; k0 < kGrid; ++k0) {
        const double m = std::sqrt(std::norm(sums.at_k0(0, k0)));  // no hypot: values of order 1
        b.min = std::min(b.min, m);
        b.max = std::max(b.max, m);
      }
    }
  }
  return b;
}

LatticeTaps convolve(const LatticeTaps& p, const LatticeTaps& q) {
  std::map<std::array<int, 3>, double> sum;
  for (const auto& [o, w] : p)
    for (const auto& [t, v] : q) sum[{o[0] + t[0], o[1] + t[1], o[2] + t[2]}] += w * v;
  LatticeTaps out;
  for (const auto& [o, w] : sum)
    if (w != 0) out.push_back({o, w});
  return out;
}

// The Laplacian's steps are the shortest lattice vectors, with the next shells of lattice points
// by length while those do not generate L: a rule of the lattice alone (no basis enters, so D is
// as symmetric as L), whose symbol 2 sum_t (1 - cos w.t) vanishes exactly on the dual lattice
// 2 pi L*, where the filter's response must stay 1. Its power m = ceil(k / 4) makes |D|^2 vanish
// to order 4 m >= k there, so that regularisation keeps the reproduction of polynomials of
// degree < k.
LatticeTaps regulariser_taps(const std::vector<std::vector<std::int64_t>>& basis, int order) {
  const Membership lattice(basis);
  const std::size_t n = basis.size();
  // In n <= 3 dimensions vectors attaining the successive minima form a basis of L, and those
  // are at most d long (d Z^n lies inside L): the shells within |x| <= d generate L.
  const std::int64_t r = lattice.period();
  const std::int64_t rz = n > 2 ? r : 0, ry = n > 1 ? r : 0;
  std::map<std::int64_t, std::vector<Vec3>> shells;  // by squared length, each in z, y, x order
  for (std::int64_t z = -rz; z <= rz; ++z)
    for (std::int64_t y = -ry; y <= ry; ++y)
      for (std::int64_t x = -r; x <= r; ++x) {
        const Vec3 p{x, y, z};
        if ((x != 0 || y != 0 || z != 0) && norm2(p) <= r * r && lattice.contains(p))
          shells[norm2(p)].push_back(p);
      }
  std::vector<Vec3> steps;
  for (const auto& [length, shell] : shells) {
    steps.insert(steps.end(), shell.begin(), shell.end());
    if (minors_gcd(steps, n) == lattice.index()) break;
  }
  LatticeTaps laplacian{{{0, 0, 0}, static_cast<double>(steps.size())}};
  for (const auto& t : steps)  // each t and -t: 2 - 2 cos w.t
    laplacian.push_back(
        {{static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2])}, -1.0});
  LatticeTaps out = laplacian;
  for (int m = 1; m < (std::max(order, 4) + 3) / 4; ++m) out = convolve(out, laplacian);
  return out;
}

Regularisation regularisation(const LatticeTaps& values,
                              const std::vector<std::vector<std::int64_t>>& basis, int order,
                              std::optional<double> lambda, std::string_view name) {
  Regularisation r{symbol_bounds(values), 0, 0, {}};
  const bool vanishes = r.symbol.min < kVanishing * r.symbol.max;
  if (lambda) {
    const double l = *lambda;
    if (!std::isfinite(l) || l < 0 || l > 1)
      throw std::invalid_argument(
          fmt::format("interpolation lambda {} must be finite and in [0, 1]", l));
    if (l == 0 && vanishes)
      throw std::invalid_argument(fmt::format(
          "the symbol of filter {} vanishes (min |A| = {:.3g} max |A|): exact interpolation is "
          "ill posed; use interp:LAMBDA with LAMBDA > 0 (default {})",
          name, r.symbol.min / r.symbol.max, kDefaultLambda));
    r.lambda = l;
  } else {
    r.lambda = vanishes ? kDefaultLambda : 0;
  }
  if (r.lambda > 0) {
    // lambda weighs the regulariser against the filter where each is largest.
    r.regulariser = regulariser_taps(basis, order);
    const SymbolBounds d = symbol_bounds(r.regulariser);
    r.mu = r.lambda * r.symbol.max * r.symbol.max / (d.max * d.max);
  }
  return r;
}

}  // namespace boxgen::support
