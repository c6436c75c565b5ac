#include "generator/ginac_bridge.h"

#include <algorithm>
#include <sstream>

#include "generator/error.h"

namespace boxgen::generator {

namespace {

std::string text_of(const GiNaC::ex& e) {
  std::ostringstream os;
  os << e;
  return os.str();
}

}  // namespace

const std::vector<GiNaC::symbol>& coordinate_symbols(int n) {
  static const std::vector<GiNaC::symbol> xyz{GiNaC::symbol("x"), GiNaC::symbol("y"),
                                              GiNaC::symbol("z")};
  static const std::vector<GiNaC::symbol> xy{xyz[0], xyz[1]};
  if (n == 2) return xy;
  if (n == 3) return xyz;
  fail_internal("coordinate symbols exist for 2 and 3 dimensions only");
}

GiNaC::numeric to_numeric(const Rational& r) { return GiNaC::numeric(cln::cl_N(r)); }

Rational to_rational(const GiNaC::numeric& n) {
  if (!n.is_rational()) fail_input("expected a rational number, got " + text_of(n));
  return cln::the<Rational>(n.to_cl_N());
}

GiNaC::ex to_ex(const Poly& p, const std::vector<GiNaC::symbol>& vars) {
  const int n = p.vars();
  if (static_cast<int>(vars.size()) != n) fail_internal("to_ex: one symbol per variable is needed");
  const auto& exponents = monomial_exponents(n, p.capacity());
  GiNaC::exvector terms;
  for (std::size_t i = 0; i < p.coefficients().size(); ++i) {
    const Rational& c = p.coefficients()[i];
    if (cln::zerop(c)) continue;
    GiNaC::ex term = to_numeric(c);
    for (int k = 0; k < n; ++k)
      if (exponents[i][k] > 0) term *= GiNaC::pow(vars[k], exponents[i][k]);
    terms.push_back(term);
  }
  return GiNaC::add(terms);
}

GiNaC::ex to_ex(const Poly& p) { return to_ex(p, coordinate_symbols(p.vars())); }

namespace {

// One term c * x^a * y^b * ...: adds its exponents to e and returns c.
GiNaC::numeric split_monomial(const GiNaC::ex& term, const std::vector<GiNaC::symbol>& vars,
                              Exponent& e) {
  GiNaC::numeric coefficient = 1;
  const GiNaC::exvector factors = GiNaC::is_a<GiNaC::mul>(term)
                                      ? GiNaC::exvector(term.begin(), term.end())
                                      : GiNaC::exvector{term};
  for (const auto& f : factors) {
    if (GiNaC::is_a<GiNaC::numeric>(f)) {
      coefficient *= GiNaC::ex_to<GiNaC::numeric>(f);
      continue;
    }
    GiNaC::ex base = f;
    int power = 1;
    if (GiNaC::is_a<GiNaC::power>(f)) {
      base = f.op(0);
      const GiNaC::ex exponent = f.op(1);
      if (!GiNaC::is_a<GiNaC::numeric>(exponent) ||
          !GiNaC::ex_to<GiNaC::numeric>(exponent).is_pos_integer())
        fail_input("not a polynomial: " + text_of(f));
      power = GiNaC::ex_to<GiNaC::numeric>(exponent).to_int();
    }
    const auto it = std::find_if(vars.begin(), vars.end(),
                                 [&](const GiNaC::symbol& s) { return base.is_equal(s); });
    if (it == vars.end()) fail_input("unexpected factor in a polynomial: " + text_of(f));
    e[static_cast<std::size_t>(it - vars.begin())] += power;
  }
  return coefficient;
}

}  // namespace

Poly to_poly(const GiNaC::ex& e, const std::vector<GiNaC::symbol>& vars) {
  const int n = static_cast<int>(vars.size());
  const GiNaC::ex expanded = e.expand();
  const GiNaC::exvector terms = GiNaC::is_a<GiNaC::add>(expanded)
                                    ? GiNaC::exvector(expanded.begin(), expanded.end())
                                    : GiNaC::exvector{expanded};
  std::vector<std::pair<Exponent, Rational>> monomials;
  int degree = 0;
  for (const auto& term : terms) {
    if (term.is_zero()) continue;
    Exponent ex{0, 0, 0};
    const Rational c = to_rational(split_monomial(term, vars, ex));
    if (ex[0] + ex[1] + ex[2] > 64) fail_input("polynomial degree above 64");
    degree = std::max(degree, ex[0] + ex[1] + ex[2]);
    monomials.emplace_back(ex, c);
  }
  Poly p(n, degree);
  for (const auto& [ex, c] : monomials) p.set_coefficient(ex, p.coefficient(ex) + c);
  p.trim();
  return p;
}

}  // namespace boxgen::generator
