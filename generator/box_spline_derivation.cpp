#include "generator/box_spline_derivation.h"

#include "generator/error.h"
#include "generator/knot_normals.h"

namespace boxgen::generator {

std::unique_ptr<BoxSplineDerivation> BoxSplineDerivation::make(const IntColumns& directions, int n,
                                                               DerivationMethod m) {
  if (m == DerivationMethod::TruncatedPower)
    return std::make_unique<TruncatedPowerDerivation>(directions, n);
  return std::make_unique<DirectionalIntegrationDerivation>(directions, n);
}

DirectionalIntegrationDerivation::DirectionalIntegrationDerivation(const IntColumns& directions,
                                                                   int n)
    : integrator_(basis_first(directions, n), n, IntegrationPath::UnitSegment) {}

HalfSpaceFlip flip_into_half_space(const IntColumns& directions, int n) {
  // Entries are bounded by 64 (spec validation), so h = (1, 1000, 10^6) separates every column.
  const IntVec h = n == 2 ? IntVec{1, 1000} : IntVec{1, 1000, 1000000};
  HalfSpaceFlip f{{}, IntVec(n, 0)};
  for (const auto& xi : directions) {
    const std::int64_t s = dot(h, xi);
    if (s == 0) fail_internal("flip_into_half_space: zero column");
    if (s > 0) {
      f.columns.push_back(xi);
    } else {
      IntVec neg = xi;
      for (auto& v : neg) v = -v;
      f.columns.push_back(neg);
      for (int i = 0; i < n; ++i) f.delta[i] += xi[i];
    }
  }
  return f;
}

namespace {

std::map<IntVec, Integer> difference_shifts(const HalfSpaceFlip& f) {
  // sum over sub-multisets S of (-1)^|S| at the shift delta + sum(S), grouped by shift.
  std::map<IntVec, Integer> w{{f.delta, Integer(1)}};
  for (const auto& xi : f.columns) {
    std::map<IntVec, Integer> next = w;
    for (const auto& [s, c] : w) {
      IntVec t = s;
      for (size_t i = 0; i < t.size(); ++i) t[i] += xi[i];
      next[t] = next[t] - c;
    }
    w.clear();
    for (auto& [s, c] : next)
      if (!cln::zerop(c)) w.emplace(s, c);
  }
  return w;
}

}  // namespace

TruncatedPowerDerivation::TruncatedPowerDerivation(const IntColumns& directions, int n)
    : n_(n),
      integrator_(basis_first(flip_into_half_space(directions, n).columns, n), n,
                  IntegrationPath::Ray) {
  for (auto& [s, w] : difference_shifts(flip_into_half_space(directions, n))) {
    std::vector<std::int64_t> dots;
    for (const auto& nu : integrator_.top_planes().normals) dots.push_back(dot(nu, s));
    normal_dot_shift_.push_back(std::move(dots));
    shifts_.emplace_back(s, w);
  }
}

Poly TruncatedPowerDerivation::polynomial_at(const RatVec& p) {
  // T's cells are keyed by the signs of nu . (p - s); with p = P / d, P integral, that is the
  // sign of nu . P - d nu . s, computed once per normal and then in integers per shift.
  const auto& normals = integrator_.top_planes().normals;
  Integer d = 1;
  for (const auto& x : p) d = cln::lcm(d, cln::denominator(x));
  std::vector<Integer> nu_p;
  for (const auto& nu : normals) {
    Integer v = 0;
    for (int i = 0; i < n_; ++i) v = v + nu[i] * cln::numerator(p[i] * d);
    nu_p.push_back(v);
  }
  std::vector<const ScaledPoly*> terms;
  CellKey key(normals.size());
  for (size_t k = 0; k < shifts_.size(); ++k) {
    for (size_t i = 0; i < normals.size(); ++i)
      key[i] = cln::plusp(nu_p[i] - d * normal_dot_shift_[k][i]) ? 0 : -1;  // sign_key convention
    auto memo_key = std::make_pair(key, static_cast<int>(k));
    auto it = translated_.find(memo_key);
    if (it == translated_.end()) {
      const auto& [s, w] = shifts_[k];
      RatVec q = p;
      for (int i = 0; i < n_; ++i) q[i] = q[i] - Rational(s[i]);
      const Poly& t = integrator_.top(key, q);
      it =
          translated_
              .emplace(memo_key, scaled(t.is_zero() ? t : t.translated(to_ratvec(s)) * Rational(w)))
              .first;
    }
    if (!it->second.is_zero()) terms.push_back(&it->second);
  }
  Poly sum = sum_scaled(n_, terms);
  sum.trim();
  return sum;
}

}  // namespace boxgen::generator
