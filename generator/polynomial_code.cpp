#include "generator/polynomial_code.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "generator/code_text.h"
#include "generator/embedded_templates.h"
#include "generator/error.h"

namespace boxgen {

using code::join;
using code::literal;

EmissionStrategy parse_strategy(std::string_view name) {
  if (name == "monomial") return EmissionStrategy::Monomial;
  if (name == "horner") return EmissionStrategy::Horner;
  fail_input("--strategy must be monomial or horner, got '" + std::string(name.substr(0, 40)) + "'");
}

const char* strategy_name(EmissionStrategy s) { return s == EmissionStrategy::Monomial ? "monomial" : "horner"; }

namespace {

// sum_k w_k v[k] for one monomial; with `grouped`, values sharing |w| share one multiplication.
std::string linear_combination(const ReferenceRegion& ref, std::size_t m, bool grouped) {
  struct Group {
    Rational weight;  // > 0
    std::string sum;
    int count = 0;
  };
  std::vector<Group> groups;
  std::vector<std::string> terms;
  for (std::size_t k = 0; k < ref.basis.size(); ++k) {
    const auto& cs = ref.basis[k].coefficients();
    if (m >= cs.size() || cln::zerop(cs[m])) continue;
    const Rational& w = cs[m];
    if (!grouped) {
      terms.push_back(fmt::format("T({}) * v[{}]", literal(w), k));
      continue;
    }
    const Rational magnitude = cln::abs(w);
    const bool negative = cln::minusp(w);
    auto it = std::find_if(groups.begin(), groups.end(), [&](const Group& g) { return g.weight == magnitude; });
    if (it == groups.end()) {
      groups.push_back({magnitude, fmt::format("{}v[{}]", negative ? "-" : "", k), 1});
    } else {
      it->sum += fmt::format(" {} v[{}]", negative ? "-" : "+", k);
      ++it->count;
    }
  }
  if (grouped)
    for (const auto& g : groups)
      terms.push_back(g.weight == 1   ? "(" + g.sum + ")"
                      : g.count == 1 ? fmt::format("T({}) * {}", literal(g.weight), g.sum)
                                     : fmt::format("T({}) * ({})", literal(g.weight), g.sum));
  return join(terms, " + ");
}

// Names of the coefficient variables c<m> of the monomials that occur, and their definitions.
struct Coefficients {
  std::vector<std::size_t> used;  // monomial indices
  std::string definitions;
};

Coefficients coefficients(const ReferenceRegion& ref, int n, int degree, bool grouped) {
  Coefficients c;
  for (std::size_t m = 0; m < monomial_count(n, degree); ++m) {
    const std::string sum = linear_combination(ref, m, grouped);
    if (sum.empty()) continue;
    c.used.push_back(m);
    c.definitions += fmt::format("  const T c{} = {};\n", m, sum);
  }
  return c;
}

std::string orbit_header_args(const ReferenceRegion& ref) {
  std::vector<std::string> verts;
  for (const auto& v : ref.vertices) verts.push_back(code::vertex_text(v));
  return join(verts, " ");
}

std::string monomial_function(const ReferenceRegion& ref, int orbit, int n, int degree) {
  const auto& exps = monomial_exponents(n, degree);
  const Coefficients c = coefficients(ref, n, degree, false);
  std::string value_terms;
  std::vector<std::string> grad_terms(n);
  for (std::size_t m : c.used) {
    std::string power;
    for (int i = 0; i < n; ++i)
      if (exps[m][i]) power += fmt::format(" * p[{}][{}]", i, exps[m][i]);
    value_terms += fmt::format("\n      + c{}{}", m, power);
    for (int d = 0; d < n; ++d) {
      if (!exps[m][d]) continue;
      std::string g = fmt::format("T({}) * c{}", exps[m][d], m);
      for (int i = 0; i < n; ++i) {
        const int e = exps[m][i] - (i == d ? 1 : 0);
        if (e) g += fmt::format(" * p[{}][{}]", i, e);
      }
      grad_terms[d] += "\n        + " + g;
    }
  }
  std::string evaluation = fmt::format("  const T value = T(0){};\n  if (gradient) {{\n", value_terms);
  for (int d = 0; d < n; ++d) evaluation += fmt::format("    gradient[{}] = T(0){};\n", d, grad_terms[d]);
  evaluation += "  }\n  return value;";
  return fmt::format(fmt::runtime(templates::orbit_monomial), fmt::arg("orbit", orbit),
                     fmt::arg("vertices", orbit_header_args(ref)), fmt::arg("monomials", c.used.size()),
                     fmt::arg("stencil", ref.stencil.size()), fmt::arg("coefficients", c.definitions),
                     fmt::arg("evaluation", evaluation));
}

// Nested Horner form of sum_e coefficient(e) x^e, variables from `var` on: the outer variable is
// factored out power by power, the remaining ones recursively.
std::string horner(const std::map<Exponent, std::string>& terms, int var, int n) {
  if (terms.empty()) return "";
  if (var == n) return terms.begin()->second;  // every exponent is used up: one term left
  std::map<int, std::map<Exponent, std::string>> by_power;
  for (const auto& [e, text] : terms) by_power[e[var]].emplace(e, text);
  const int top = by_power.rbegin()->first;
  std::string acc = horner(by_power[top], var + 1, n);
  for (int a = top - 1; a >= 0; --a) {
    const auto it = by_power.find(a);
    const std::string inner = it == by_power.end() ? "" : horner(it->second, var + 1, n);
    acc = fmt::format("{}{}x[{}] * ({})", inner, inner.empty() ? "" : " + ", var, acc);
  }
  return acc;
}

std::string horner_function(const ReferenceRegion& ref, int orbit, int n, int degree) {
  const auto& exps = monomial_exponents(n, degree);
  const Coefficients c = coefficients(ref, n, degree, true);
  std::map<Exponent, std::string> value_terms;
  std::vector<std::map<Exponent, std::string>> grad_terms(n);
  for (std::size_t m : c.used) {
    value_terms.emplace(exps[m], fmt::format("c{}", m));
    for (int d = 0; d < n; ++d) {
      if (!exps[m][d]) continue;
      Exponent lowered = exps[m];
      --lowered[d];
      grad_terms[d].emplace(lowered, exps[m][d] == 1 ? fmt::format("c{}", m) : fmt::format("T({}) * c{}", exps[m][d], m));
    }
  }
  std::string gradient;
  for (int d = 0; d < n; ++d) {
    const std::string g = horner(grad_terms[d], 0, n);
    gradient += fmt::format("    gradient[{}] = {};\n", d, g.empty() ? "T(0)" : g);
  }
  if (!gradient.empty()) gradient.pop_back();
  const std::string value = horner(value_terms, 0, n);
  return fmt::format(fmt::runtime(templates::orbit_horner), fmt::arg("orbit", orbit),
                     fmt::arg("vertices", orbit_header_args(ref)), fmt::arg("monomials", c.used.size()),
                     fmt::arg("stencil", ref.stencil.size()), fmt::arg("coefficients", c.definitions),
                     fmt::arg("gradient", gradient), fmt::arg("value", value.empty() ? "T(0)" : value));
}

}  // namespace

std::string orbit_function(const ReferenceRegion& ref, int orbit, int n, int degree, EmissionStrategy strategy) {
  return strategy == EmissionStrategy::Monomial ? monomial_function(ref, orbit, n, degree)
                                                : horner_function(ref, orbit, n, degree);
}

}  // namespace boxgen
