// The interpolation symbol A(w) = sum_k M(k) e^(-i w.k) (docs/design.md §18) and the FIR
// interpolation prefilter qfir:K. The lattice samples M(k) come from the derived pieces; here they
// are checked against limits of the de Boor-Hoellig recurrence (§2), which shares nothing with the
// pieces and is valid only at generic points: M(k) = lim M_Xi(k + c + eps v) as eps -> 0, the
// values along the segment being one polynomial in eps of degree at most m - n.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "generator/approximation_order.h"
#include "generator/error.h"
#include "generator/interpolation_symbol.h"
#include "generator/prefilter.h"
#include "generator/rational_linear_systems.h"
#include "generator/recurrence.h"
#include "support/fir_prefilter.hpp"
#include "tests/generator/derivation_fixture.h"

namespace boxgen::generator {
namespace {

using fixture::derivation_of;

// Newton's interpolating polynomial through (x_k, y_k), evaluated at 0.
Rational value_at_zero(const RatVec& x, RatVec y) {
  const std::size_t count = x.size();
  for (std::size_t level = 1; level < count; ++level)
    for (std::size_t k = count - 1; k >= level; --k)
      y[k] = (y[k] - y[k - 1]) / (x[k] - x[k - level]);
  Rational value = y[count - 1];
  for (std::size_t k = count - 1; k-- > 0;) value = value * (0 - x[k]) + y[k];
  return value;
}

// M(k) for every lattice point k of a box around the support, by the recurrence's limits.
std::map<IntVec, Rational> samples_by_recurrence(const BoxSplineSpec& spec) {
  const int n = spec.dimension();
  const int degree = spec.count() - n;
  // v = (1, P, P^2) with P beyond every normal's entries: nu.v != 0 for every knot normal, and
  // eps |nu.v| < 1/2 keeps k + c + eps v off every integer level (nu.(k + c) lies in Z/2).
  const auto normals = knot_plane_normals(spec.directions);
  std::int64_t p = 1, largest = 1;
  for (const auto& nu : normals)
    for (auto x : nu) p = std::max<std::int64_t>(p, std::llabs(x) + 1);
  IntVec v(n);
  for (int i = 0, power = 1; i < n; ++i, power *= static_cast<int>(p)) v[i] = power;
  for (const auto& nu : normals) largest = std::max<std::int64_t>(largest, std::llabs(dot(nu, v)));
  const int count = degree + 3;  // two more than the polynomial needs
  RatVec centre(n, 0), eps(count);
  for (const auto& xi : spec.directions)
    for (int i = 0; i < n; ++i) centre[i] = centre[i] + fraction(xi[i], 2);
  IntVec lo(n), hi(n);
  for (int i = 0; i < n; ++i) {
    std::int64_t reach = 0;
    for (const auto& xi : spec.directions) reach += std::llabs(xi[i]);
    lo[i] = -reach;
    hi[i] = reach;
  }
  const std::vector<IntVec> points = spec.lattice.points_in_box(lo, hi);
  std::vector<RatVec> values(points.size(), RatVec(count));
  BoxSplineRecurrence recurrence(spec.directions);
  for (int e = 0; e < count; ++e) {
    eps[e] = fraction(e + 1, 4 * largest * count);
    RatVec base = centre;
    for (int i = 0; i < n; ++i) base[i] = base[i] + eps[e] * rational_from(v[i]);
    recurrence.set_base(base);
    for (std::size_t j = 0; j < points.size(); ++j) values[j][e] = recurrence.at_shift(points[j]);
  }
  std::map<IntVec, Rational> out;
  const Rational scale = rational_from(spec.lattice.det_abs());
  for (std::size_t j = 0; j < points.size(); ++j) {
    // The last two values confirm the polynomial through the others.
    const RatVec x(eps.begin(), eps.end() - 2);
    const RatVec y(values[j].begin(), values[j].end() - 2);
    for (int extra = count - 2; extra < count; ++extra) {
      RatVec shifted = x;
      for (auto& t : shifted) t = t - eps[extra];
      EXPECT_EQ(value_at_zero(shifted, y), values[j][extra]) << "not one polynomial in eps";
    }
    const Rational limit = value_at_zero(x, y) * scale;
    if (!cln::zerop(limit)) out[points[j]] = limit;
  }
  return out;
}

TEST(InterpolationSymbol, LatticeSamplesAreTheRecurrencesLimits) {
  for (const char* preset : {"m7", "m8", "m12", "fcc6", "tricubic", "cart7", "zp", "hex3"}) {
    const Derivation& a = derivation_of(preset);
    const auto samples = lattice_samples(a.form);
    const auto expected = samples_by_recurrence(a.spec);
    ASSERT_EQ(samples.size(), expected.size()) << preset;
    Rational sum = 0;
    for (const auto& s : samples) {
      ASSERT_TRUE(expected.count(s.point)) << preset;
      EXPECT_EQ(s.value, expected.at(s.point)) << preset;
      sum = sum + s.value;
    }
    EXPECT_EQ(sum, 1) << preset << ": the shifts sum to one, so A(0) = 1";
  }
}

TEST(InterpolationSymbol, M7SamplesAndItsZeroByHand) {
  // M7: M(0) = 3/8, 1/16 on the 8 nearest neighbours, 1/48 on the 6 second ones, so
  // A(w) = 3/8 + (1/2) c1 c2 c3 + (1/24) sum cos(2 w_i) = 1/4 + (1/2) c1 c2 c3 + (1/12) sum c_i^2
  // with c_i = cos w_i: zero exactly where |c_i| = 1 and c1 c2 c3 = -1, i.e. w = pi (1,0,0) and the
  // points equivalent to it modulo the dual lattice pi (a,b,c), a + b + c even.
  const auto samples = lattice_samples(derivation_of("m7").form);
  ASSERT_EQ(samples.size(), 15u);
  for (const auto& s : samples) {
    const std::int64_t norm = dot(s.point, s.point);
    EXPECT_EQ(s.value, norm == 0 ? fraction(3, 8) : norm == 3 ? fraction(1, 16) : fraction(1, 48));
  }
  EXPECT_EQ(*symbol_at(samples, {0, 0, 0}), 1);
  EXPECT_EQ(*symbol_at(samples, {1, 0, 0}), 0);
  EXPECT_EQ(*symbol_at(samples, {1, 1, 1}), 0);
  EXPECT_EQ(*symbol_at(samples, {fraction(1, 2), fraction(1, 2), fraction(1, 2)}), fraction(1, 4));
  EXPECT_FALSE(symbol_at(samples, {fraction(1, 4), 0, 0}));  // cos(pi / 4) is irrational
  const ExactSymbolValues v = exact_symbol_values(samples, Lattice::bcc());
  EXPECT_EQ(v.min_abs, 0);
  ASSERT_EQ(v.zeros.size(), 1u);
  const std::vector<RatVec> expected = {{1, 0, 0},  {0, 1, 0},  {0, 0, 1},
                                        {0, 0, -1}, {0, -1, 0}, {-1, 0, 0}};
  EXPECT_EQ(v.zeros[0].representatives, expected);
}

TEST(InterpolationSymbol, M8IsWellPosedWithMinimumOneFifth) {
  // M8: M(0) = 2/5, 1/20 and 1/30: A(w) = 1/5 + (2/5) c1 c2 c3 + (2/15) sum c_i^2 >= 1/5, with
  // equality at c = 0 (w = pi (1/2,1/2,1/2)) and at c = (-1,1,1) (w = pi (1,0,0)).
  const auto samples = lattice_samples(derivation_of("m8").form);
  const ExactSymbolValues v = exact_symbol_values(samples, Lattice::bcc());
  EXPECT_TRUE(v.zeros.empty());
  EXPECT_EQ(v.min_abs, fraction(1, 5));
  bool corner = false, centre = false;
  for (const auto& c : v.min_at)
    for (const auto& r : c.representatives) {
      corner = corner || r == RatVec{1, 0, 0};
      centre = centre || r == RatVec{fraction(1, 2), fraction(1, 2), fraction(1, 2)};
    }
  EXPECT_TRUE(corner && centre);
}

TEST(InterpolationSymbol, DiscontinuousFiltersHaveNoSamples) {
  EXPECT_THROW(lattice_samples(parse_spec("1,0; 0,1")), InputError);
}

// The exact optimality of qfir: the weights satisfy the moment conditions, and the residual at the
// samples, smoothed s times by M (s = kQfirSmoothing), is orthogonal to every direction d that
// keeps them, smoothed alike: sum_j (M^s * (M * q - delta))(j) (M^(s+1) * d)(j) = 0, the gradient
// of qfir's objective (a null space computed by the generator's own exact solver, not the FIR
// solver's, and the convolutions here).
TEST(FirPrefilter, IsTheLeastSquaresSolutionExactly) {
  for (const char* preset : {"m7", "m8", "fcc6"}) {
    const Derivation& a = derivation_of(preset);
    const auto samples = lattice_samples(a.form);
    const Prefilter q = derive_fir_prefilter(a.spec, 3, samples);
    EXPECT_EQ(q.parametrisation, "fir");
    const int n = a.spec.dimension();
    // r = M * q and, for a change d of the weights, M * d, on the lattice points they reach.
    const auto convolve = [&](const std::vector<std::pair<IntVec, Rational>>& taps) {
      std::map<IntVec, Rational> out;
      for (const auto& [o, w] : taps)
        for (const auto& s : samples) {
          IntVec j = o;
          for (int i = 0; i < n; ++i) j[i] += s.point[i];
          out[j] = out[j] + w * s.value;
        }
      return out;
    };
    std::vector<std::pair<IntVec, Rational>> taps;
    for (const auto& w : q.weights) taps.emplace_back(w.offset, w.weight);
    std::map<IntVec, Rational> r = convolve(taps);
    r[IntVec(n, 0)] = r[IntVec(n, 0)] - 1;  // the residual r - delta
    // Moment rows sum_j (M * d)(j) j^a for |a| < order, one column per tap.
    const int order = approximation_order(a.spec.directions, n);
    std::vector<RatVec> rows;
    const auto below_order = [&](const Exponent& e) { return e[0] + e[1] + e[2] < order; };
    for (const auto& e : monomial_exponents(n, order - 1)) {
      if (!below_order(e)) break;  // the list may go on to higher degrees
      RatVec row(taps.size());
      for (std::size_t t = 0; t < taps.size(); ++t)
        for (const auto& [j, m] : convolve({{taps[t].first, Rational(1)}})) {
          Rational power = 1;
          for (int i = 0; i < n; ++i)
            for (int k = 0; k < e[i]; ++k) power = power * rational_from(j[i]);
          row[t] = row[t] + m * power;
        }
      rows.push_back(row);
    }
    // The conditions hold: the moments of r + delta are those of delta.
    for (const auto& e : monomial_exponents(n, order - 1)) {
      if (!below_order(e)) break;
      Rational moment = 0;
      for (const auto& [j, v] : r) {
        Rational power = 1;
        for (int i = 0; i < n; ++i)
          for (int k = 0; k < e[i]; ++k) power = power * rational_from(j[i]);
        moment = moment + v * power;
      }
      EXPECT_EQ(moment, 0) << preset;
    }
    const auto directions = null_space(rows, static_cast<int>(taps.size()));
    ASSERT_FALSE(directions.empty()) << preset;
    const auto smooth = [&](std::map<IntVec, Rational> v) {
      for (int s = 0; s < support::kQfirSmoothing; ++s)
        v = convolve(std::vector<std::pair<IntVec, Rational>>(v.begin(), v.end()));
      return v;
    };
    const std::map<IntVec, Rational> residual = smooth(r);
    for (const auto& d : directions) {
      std::vector<std::pair<IntVec, Rational>> change;
      for (std::size_t t = 0; t < taps.size(); ++t) change.emplace_back(taps[t].first, d[t]);
      Rational inner = 0;
      for (const auto& [j, m] : smooth(convolve(change)))
        if (residual.count(j)) inner = inner + m * residual.at(j);
      EXPECT_EQ(inner, 0) << preset;
    }
  }
}

TEST(FirPrefilter, TooFewShellsNameTheLeastThatSuffice) {
  const Derivation& a = derivation_of("m7");
  const auto samples = lattice_samples(a.form);
  try {
    (void)derive_fir_prefilter(a.spec, 0, samples);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("qfir:1"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)derive_fir_prefilter(a.spec, kMaxPrefilterShell + 1, samples), InputError);
  EXPECT_THROW((void)named_prefilter(a.spec, "qfir:x"), InputError);
  EXPECT_THROW((void)named_prefilter(a.spec, "q3"), InputError);
}

}  // namespace
}  // namespace boxgen::generator
