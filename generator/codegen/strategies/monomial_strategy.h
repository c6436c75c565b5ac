// The `monomial` strategy (polynomial_code.h): one coefficient per monomial, each a linear
// combination of the stencil values, times a table of coordinate powers shared between the value
// and the derivatives.
#pragma once
#include <optional>

#include "generator/codegen/strategies/polynomial_code.h"

namespace boxgen::generator::strategies {

std::optional<OrbitCode> monomial_code(const ReferenceRegion& ref, int orbit, int n, int degree);

}  // namespace boxgen::generator::strategies
