#include "generator/codegen/strategies/monomial_strategy.h"

#include <fmt/format.h>

#include <utility>

#include "generator/codegen/strategies/strategy_builders.h"
#include "generator/embedded_templates.h"

namespace boxgen::generator::strategies {

std::optional<OrbitCode> monomial_code(const ReferenceRegion& ref, int orbit, int n, int degree) {
  Build b;
  const Coefficients c = coefficients(b, ref.basis, n, degree, false);
  // p[i][e] = x_i^e, and each monomial once.
  const std::vector<NodeId> x = b.coordinates(n);
  std::vector<std::vector<NodeId>> power(n, {b.g.constant(1)});
  for (int i = 0; i < n; ++i)
    for (int e = 1; e <= degree; ++e) {
      power[i].push_back(generator::product(b.g, power[i].back(), x[i]));
      b.name(power[i].back(), fmt::format("p{}_{}", i, e));
    }
  auto monomial = [&](const Exponent& e) {
    NodeId m = b.g.constant(1);
    for (int i = 0; i < n; ++i) m = generator::product(b.g, m, power[i][e[i]]);
    return m;
  };
  const auto derivatives = derivative_indices(n, 2);
  NodeId value = b.zero();
  std::vector<NodeId> d(derivatives.size(), b.zero());
  for (const auto& [e, coefficient] : c.node) {
    value = generator::sum(b.g, value, generator::product(b.g, coefficient, monomial(e)));
    for (std::size_t k = 0; k < derivatives.size(); ++k) {
      Exponent lowered{0, 0, 0};
      const long factor = derivative_factor(e, derivatives[k], lowered);
      if (!factor) continue;
      const NodeId term = generator::scaled(b.g, Rational(factor), coefficient);
      d[k] = generator::sum(b.g, d[k], generator::product(b.g, term, monomial(lowered)));
    }
  }
  return finish(std::move(b), EmissionStrategy::Monomial, value, d, n,
                {templates::orbit_monomial,
                 {{"orbit", std::to_string(orbit)},
                  {"vertices", orbit_vertices(ref)},
                  {"monomials", std::to_string(c.node.size())},
                  {"stencil", std::to_string(ref.stencil.size())}}});
}

}  // namespace boxgen::generator::strategies
