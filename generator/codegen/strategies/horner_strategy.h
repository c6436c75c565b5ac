// The `horner` strategy (polynomial_code.h): the monomial coefficients in nested Horner form, each
// partial derivative differentiating that Horner form. `shifted` (shifted_strategy.h) builds the
// same form in other variables.
#pragma once
#include <optional>
#include <vector>

#include "generator/codegen/strategies/polynomial_code.h"
#include "generator/codegen/strategies/strategy_builders.h"

namespace boxgen::generator::strategies {

// The Horner form of the basis in the variables `vars`; value and derivative nodes (in the order
// of derivative_indices(n, 2)) returned.
struct HornerNodes {
  NodeId value;
  std::vector<NodeId> derivatives;
  std::size_t monomials = 0, shared_sums = 0;
};
HornerNodes horner_nodes(Build& b, const std::vector<Poly>& basis, int n, int degree,
                         const std::vector<NodeId>& vars);

std::optional<OrbitCode> horner_code(const ReferenceRegion& ref, int orbit, int n, int degree);

}  // namespace boxgen::generator::strategies
