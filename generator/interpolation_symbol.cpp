#include "generator/interpolation_symbol.h"

#include <algorithm>
#include <map>
#include <set>

#include "generator/approximation_order.h"
#include "generator/error.h"
#include "generator/zonotope.h"

namespace boxgen::generator {

namespace {

// cos(pi t) where it is rational: t in Z/2 or Z/3 (Niven's theorem), else nullopt.
std::optional<Rational> cos_pi(const Rational& t) {
  const Rational u = t - 2 * floor_rational(t / 2);  // in [0, 2)
  const Rational sixths = u * 6;
  if (!is_integer(sixths)) return std::nullopt;
  switch (floor_to_int64(sixths)) {
    case 0:
      return Rational(1);
    case 2:
    case 10:
      return fraction(1, 2);
    case 3:
    case 9:
      return Rational(0);
    case 4:
    case 8:
      return fraction(-1, 2);
    case 6:
      return Rational(-1);
    default:
      return std::nullopt;  // odd sixths: +-sqrt(3)/2
  }
}

Rational norm2(const RatVec& r) {
  Rational s = 0;
  for (const auto& x : r) s = s + x * x;
  return s;
}

// The representatives of r + 2 G^-T z nearest the origin, the lexicographically largest first:
// 2 G^-T Z^n is the dual lattice in units of pi.
std::vector<RatVec> nearest_representatives(const RatVec& r, const RatMatrix& dual_basis) {
  const int n = static_cast<int>(r.size());
  constexpr int kReach = 3;  // coefficients tried per dual basis vector
  std::vector<RatVec> best;
  Rational best_norm = -1;
  IntVec z(n, -kReach);
  for (;;) {
    RatVec p = r;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) p[i] = p[i] + 2 * rational_from(z[j]) * dual_basis[i][j];
    const Rational m = norm2(p);
    if (best_norm < 0 || m < best_norm) {
      best_norm = m;
      best.clear();
    }
    if (m == best_norm) best.push_back(p);
    int i = 0;
    while (i < n && z[i] == kReach) z[i++] = -kReach;
    if (i == n) break;
    ++z[i];
  }
  std::sort(best.begin(), best.end(), [](const RatVec& a, const RatVec& b) { return b < a; });
  return best;
}

}  // namespace

std::vector<LatticeSample> lattice_samples(const PiecewiseForm& form) {
  const BoxSplineSpec& spec = form.spec;
  const int n = spec.dimension();
  if (approximation_order(spec.directions, n) < 2)
    fail_input("the filter " + spec.name +
               " is discontinuous, so its values at the lattice points are not defined");
  RatVec centre(n, Rational(0));
  for (const auto& xi : spec.directions)
    for (int i = 0; i < n; ++i) centre[i] = centre[i] + fraction(xi[i], 2);
  const Zonotope support(spec.directions, n);
  IntVec lo(n), hi(n);  // the centred support's box, rounded inwards to integers
  for (int i = 0; i < n; ++i) {
    lo[i] = -floor_to_int64(centre[i] - rational_from(support.box_lo()[i]));
    hi[i] = floor_to_int64(rational_from(support.box_hi()[i]) - centre[i]);
  }
  const Rational scale = rational_from(spec.lattice.det_abs());
  std::vector<LatticeSample> out;
  for (const IntVec& k : spec.lattice.points_in_box(lo, hi)) {
    RatVec x(n);
    for (int i = 0; i < n; ++i) x[i] = rational_from(k[i]) + centre[i];
    const Rational v = scale * form.value_at(x);
    if (!cln::zerop(v)) out.push_back({k, v});
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.point < b.point; });
  return out;
}

std::vector<LatticeSample> lattice_samples(const BoxSplineSpec& spec) {
  return lattice_samples(derive_piecewise(spec, DerivationMethod::TruncatedPower));
}

std::optional<Rational> symbol_at(const std::vector<LatticeSample>& samples, const RatVec& r) {
  Rational a = 0;
  for (const auto& s : samples) {
    const auto c = cos_pi(dot(s.point, r));
    if (!c) return std::nullopt;
    a = a + s.value * *c;
  }
  return a;
}

ExactSymbolValues exact_symbol_values(const std::vector<LatticeSample>& samples,
                                      const Lattice& lattice) {
  const int n = lattice.dimension();
  // Columns of G^-T: the transpose of G^-1.
  const RatMatrix g_inverse = inverse(lattice.generator());
  RatMatrix dual_basis(n, RatVec(n));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) dual_basis[i][j] = g_inverse[j][i];

  // Every candidate r in [0, 2)^n with steps 1/2 or 1/3, grouped by class.
  std::map<std::vector<RatVec>, Rational> value_of_class;
  for (const int steps : {2, 3}) {
    IntVec z(n, 0);
    for (;;) {
      RatVec r(n);
      for (int i = 0; i < n; ++i) r[i] = fraction(z[i], steps);
      auto representatives = nearest_representatives(r, dual_basis);
      if (!value_of_class.count(representatives)) {
        const auto a = symbol_at(samples, r);
        if (!a) fail_internal("symbol: a candidate frequency has an irrational cosine");
        value_of_class.emplace(std::move(representatives), *a);
      }
      int i = 0;
      while (i < n && z[i] == 2 * steps - 1) z[i++] = 0;
      if (i == n) break;
      ++z[i];
    }
  }
  ExactSymbolValues out;
  out.candidates = static_cast<int>(value_of_class.size());
  bool first = true;
  for (const auto& [representatives, value] : value_of_class) {
    const Rational m = cln::abs(value);
    if (first || m < out.min_abs) {
      out.min_abs = m;
      out.min_at.clear();
      first = false;
    }
    if (m == out.min_abs) out.min_at.push_back({representatives});
    if (cln::zerop(value)) out.zeros.push_back({representatives});
  }
  return out;
}

}  // namespace boxgen::generator
