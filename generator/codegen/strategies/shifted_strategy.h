// The `shifted` strategy (polynomial_code.h): the Horner form in monomials of y = x - o about the
// exact point o of the reference region (not 0) with the fewest value + gradient operations.
#pragma once
#include <optional>

#include "generator/codegen/strategies/polynomial_code.h"

namespace boxgen::generator::strategies {

std::optional<OrbitCode> shifted_code(const ReferenceRegion& ref, int orbit, int n, int degree);

}  // namespace boxgen::generator::strategies
