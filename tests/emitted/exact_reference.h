// The exact reference of the emitted evaluators' tests (tests/emitted, tests/gpu): the spline
// s(x) = sum_j V(j) M(x - j) in exact rationals from the generator's piecewise form, for integer
// hash data V, at dyadic test points half of which lie within 1e-3 of a knot plane.
#pragma once
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "generator/box_spline_properties.h"
#include "generator/piece_checks.h"
#include "generator/piecewise_form.h"

namespace boxgen::generator::exact_reference {

constexpr double kMaxV = 1000;

inline double data_value(const IntVec& j) {
  std::uint64_t h = 1469598103934665603ull;
  for (auto v : j) h = (h ^ static_cast<std::uint64_t>(v + 4096)) * 1099511628211ull;
  return static_cast<double>(h % 2001) - kMaxV;
}

// A polynomial as integer numerators over one denominator: evaluating it at X / 2^20 needs
// integer products only (rational arithmetic would normalise by a gcd at every step).
struct IntegerPoly {
  int n = 0, degree = 0;
  std::vector<Exponent> exponents;
  std::vector<Integer> numerators;
  Integer denominator = 1;

  explicit IntegerPoly(const Poly& p) : n(p.vars()), degree(std::max(p.degree(), 0)) {
    const auto& ex = monomial_exponents(n, p.capacity());
    for (std::size_t i = 0; i < p.coefficients().size(); ++i)
      if (!cln::zerop(p.coefficients()[i]))
        denominator = cln::lcm(denominator, cln::denominator(p.coefficients()[i]));
    for (std::size_t i = 0; i < p.coefficients().size(); ++i) {
      const Rational& c = p.coefficients()[i];
      if (cln::zerop(c)) continue;
      exponents.push_back(ex[i]);
      numerators.push_back(cln::numerator(c) * cln::exquo(denominator, cln::denominator(c)));
    }
  }
  // p(X / D) with D = 2^shift, X integers.
  Rational eval(const std::vector<Integer>& x, int shift) const {
    std::vector<std::vector<Integer>> pw(n, std::vector<Integer>(degree + 1));
    for (int i = 0; i < n; ++i) {
      pw[i][0] = 1;
      for (int e = 1; e <= degree; ++e) pw[i][e] = pw[i][e - 1] * x[i];
    }
    Integer sum = 0;
    for (std::size_t t = 0; t < numerators.size(); ++t) {
      Integer term = numerators[t];
      int total = 0;
      for (int i = 0; i < n; ++i) {
        term = term * pw[i][exponents[t][i]];
        total += exponents[t][i];
      }
      sum = sum +
            cln::ash(term, static_cast<long>(shift) * (degree - total));  // times D^(degree - |e|)
    }
    return Rational(sum) / Rational(cln::ash(denominator, static_cast<long>(shift) * degree));
  }
};

constexpr int kShift = 20;  // test points are multiples of 2^-20

struct Exact {
  Rational value;
  RatVec gradient;
  RatVec hessian;               // upper triangle, row by row (xx xy xz yy yz zz)
  bool hessian_defined = true;  // false where cells around the point disagree on it
};

class Reference {
 public:
  explicit Reference(const std::string& preset, const std::string& lattice = "")
      : spec_(parse_spec(preset, lattice)),
        form_(derive_piecewise(spec_, DerivationMethod::TruncatedPower)),
        centre_(spline_centre(spec_)) {}
  int dimension() const { return spec_.dimension(); }
  bool twice_differentiable() const { return box_spline_properties(spec_).continuity >= 2; }
  const PiecewiseForm& form() const { return form_; }
  const RatVec& centre() const { return centre_; }

  Exact at(const RatVec& x) const {
    const int n = dimension();
    Exact e{0, RatVec(n, 0), RatVec(n * (n + 1) / 2, 0)};
    IntVec lo(n), hi(n);
    for (int i = 0; i < n; ++i) {
      lo[i] = floor_to_int64(x[i] + centre_[i]) - form_.complex.hi()[i];
      hi[i] = floor_to_int64(x[i] + centre_[i]) - form_.complex.lo()[i] + 1;
    }
    const Rational det = Rational(spec_.lattice.det_abs());
    for (const auto& j : spec_.lattice.points_in_box(lo, hi)) {
      RatVec u(n);
      for (int i = 0; i < n; ++i) u[i] = x[i] - Rational(j[i]) + centre_[i];
      const int cell = form_.knots.locate(u);
      if (cell < 0 || form_.polys[cell].is_zero()) continue;
      // The splines tested are C^1, so any cell whose closure holds u gives the value and gradient.
      const Rational v = Rational(static_cast<long>(data_value(j))) * det;
      std::vector<Integer> scaled(n);
      for (int i = 0; i < n; ++i) {
        const Rational s = u[i] * Rational(1L << kShift);
        if (!is_integer(s)) ADD_FAILURE() << "test point off the 2^-20 grid";
        scaled[i] = cln::numerator(s);
      }
      const auto& polys = polys_of(cell);
      e.value = e.value + v * polys[0].eval(scaled, kShift);
      for (int d = 0; d < n; ++d)
        e.gradient[d] = e.gradient[d] + v * polys[d + 1].eval(scaled, kShift);
      for (int h = 0; h < n * (n + 1) / 2; ++h)
        e.hessian[h] = e.hessian[h] + v * polys[n + 1 + h].eval(scaled, kShift);
      // On a knot plane (some nu . u an integer) a C^1 spline's second derivatives may jump.
      for (const auto& nu : form_.complex.normals())
        if (is_integer(dot(nu, u))) e.hessian_defined = false;
    }
    return e;
  }

 private:
  // The cell's polynomial and its partial derivatives, in integer form.
  const std::vector<IntegerPoly>& polys_of(int cell) const {
    auto it = cache_.find(cell);
    if (it == cache_.end()) {
      std::vector<IntegerPoly> g{IntegerPoly(form_.polys[cell])};
      for (int d = 0; d < dimension(); ++d) g.emplace_back(form_.polys[cell].derivative(d));
      for (int i = 0; i < dimension(); ++i)
        for (int j = i; j < dimension(); ++j)
          g.emplace_back(form_.polys[cell].derivative(i).derivative(j));
      it = cache_.emplace(cell, std::move(g)).first;
    }
    return it->second;
  }

  mutable std::map<int, std::vector<IntegerPoly>> cache_;
  BoxSplineSpec spec_;
  PiecewiseForm form_;
  RatVec centre_;
};

// Dyadic points in a few unit cells around the origin; every other one moved along an axis to
// within 1e-3 of a random knot plane so region boundaries are exercised.
inline std::vector<RatVec> test_points(const Reference& ref, int count) {
  std::mt19937_64 rng(2024);
  const int n = ref.dimension();
  const auto& normals = ref.form().complex.normals();
  const Rational unit = Rational(1) / Rational(1L << 20);
  std::vector<RatVec> out;
  for (int k = 0; k < count; ++k) {
    RatVec x(n);
    for (int i = 0; i < n; ++i)
      x[i] = Rational(static_cast<long>(rng() % (6L << 20)) - (3L << 20)) * unit;
    if (k % 2) {
      const IntVec& nu = normals[rng() % normals.size()];
      int axis = 0;
      while (nu[axis] == 0) ++axis;
      RatVec u(n);
      for (int i = 0; i < n; ++i) u[i] = x[i] + ref.centre()[i];
      const Rational s = dot(nu, u);
      const Rational target = floor_rational(s) + Rational(static_cast<long>(rng() % 2));
      const Rational offset = Rational(static_cast<long>(rng() % 2001) - 1000) * unit;
      x[axis] = x[axis] + (target - s) / Rational(nu[axis]);
      x[axis] = floor_rational(x[axis] / unit) * unit + offset;  // back onto the 2^-20 grid
    }
    out.push_back(x);
  }
  return out;
}

}  // namespace boxgen::generator::exact_reference
