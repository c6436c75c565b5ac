// The `bernstein` strategy (polynomial_code.h): on a simplicial reference region, the
// BB-coefficients and de Casteljau's algorithm; nullopt on other regions.
#pragma once
#include <optional>

#include "generator/codegen/strategies/polynomial_code.h"

namespace boxgen::generator::strategies {

std::optional<OrbitCode> bernstein_code(const ReferenceRegion& ref, int orbit, int n, int degree);

}  // namespace boxgen::generator::strategies
