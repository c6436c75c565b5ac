#include "generator/poly_sum.h"

#include <algorithm>

#include "generator/error.h"

namespace boxgen::generator {

Integer common_denominator(const std::vector<const Poly*>& polys) {
  Integer d = 1;
  for (const Poly* p : polys)
    for (const auto& c : p->coefficients()) {
      const Integer b = cln::denominator(c);
      // Most denominators repeat: a divisibility test is cheaper than a gcd.
      if (b != 1 && !cln::zerop(cln::mod(d, b))) d = cln::lcm(d, b);
    }
  return d;
}

std::vector<Integer> scaled_numerators(const Poly& p, const Integer& d) {
  std::vector<Integer> out;
  out.reserve(p.coefficients().size());
  for (const auto& c : p.coefficients()) {
    const Rational scaled = c * d;
    if (!is_integer(scaled)) fail_internal("a common denominator does not clear a coefficient");
    out.push_back(cln::numerator(scaled));
  }
  return out;
}

bool ScaledPoly::is_zero() const {
  return std::all_of(numerators.begin(), numerators.end(),
                     [](const Integer& v) { return cln::zerop(v); });
}

ScaledPoly scaled(const Poly& p) {
  ScaledPoly out;
  out.vars = p.vars();
  out.capacity = std::max(p.capacity(), 0);
  out.denominator = common_denominator({&p});
  out.numerators = scaled_numerators(p, out.denominator);
  return out;
}

Poly sum_scaled(int n, const std::vector<const ScaledPoly*>& terms) {
  Integer d = 1;
  int capacity = 0;
  for (const ScaledPoly* t : terms) {
    capacity = std::max(capacity, t->capacity);
    if (!cln::zerop(cln::mod(d, t->denominator))) d = cln::lcm(d, t->denominator);
  }
  std::vector<Integer> total(monomial_count(n, capacity), Integer(0));
  for (const ScaledPoly* t : terms) {
    const Integer factor = cln::exquo(d, t->denominator);
    const bool unit = factor == 1;
    for (std::size_t k = 0; k < t->numerators.size(); ++k)
      if (!cln::zerop(t->numerators[k]))
        total[k] = total[k] + (unit ? t->numerators[k] : t->numerators[k] * factor);
  }
  Poly out(n, capacity);
  const auto& exponents = monomial_exponents(n, capacity);
  for (std::size_t k = 0; k < total.size(); ++k)
    if (!cln::zerop(total[k])) out.set_coefficient(exponents[k], Rational(total[k]) / d);
  return out;
}

CommonDenominatorTerms::CommonDenominatorTerms(int n, const std::vector<const Poly*>& terms)
    : n_(n), d_(common_denominator(terms)) {
  numerators_.reserve(terms.size());
  for (const Poly* p : terms) {
    capacity_ = std::max(capacity_, p->capacity());
    numerators_.push_back(scaled_numerators(*p, d_));
  }
}

std::vector<Integer> CommonDenominatorTerms::integer_sum(const std::vector<int>& indices) const {
  std::vector<Integer> total(monomial_count(n_, capacity_), Integer(0));
  for (const int i : indices) {
    const auto& term = numerators_.at(static_cast<std::size_t>(i));
    for (std::size_t k = 0; k < term.size(); ++k) total[k] = total[k] + term[k];
  }
  return total;
}

Poly CommonDenominatorTerms::sum(const std::vector<int>& indices) const {
  const std::vector<Integer> total = integer_sum(indices);
  Poly out(n_, capacity_);
  const auto& exponents = monomial_exponents(n_, capacity_);
  for (std::size_t k = 0; k < total.size(); ++k)
    if (!cln::zerop(total[k])) out.set_coefficient(exponents[k], Rational(total[k]) / d_);
  return out;
}

bool CommonDenominatorTerms::sum_is_constant(const std::vector<int>& indices,
                                             const Rational& c) const {
  const std::vector<Integer> total = integer_sum(indices);
  // total / d == c: the constant term is c d (an integer or not equal), the others are zero.
  if (Rational(total[0]) != c * d_) return false;
  return std::all_of(total.begin() + 1, total.end(),
                     [](const Integer& v) { return cln::zerop(v); });
}

}  // namespace boxgen::generator
