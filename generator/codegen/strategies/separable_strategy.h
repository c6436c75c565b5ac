// The `separable` strategy (polynomial_code.h): where the stencil splits into full tensor grids
// of univariate factors (separable_form.h), 1-D weights per axis and a contraction per grid;
// nullopt where it does not.
#pragma once
#include <optional>

#include "generator/codegen/strategies/polynomial_code.h"

namespace boxgen::generator::strategies {

std::optional<OrbitCode> separable_code(const ReferenceRegion& ref, int orbit, int n, int degree);

}  // namespace boxgen::generator::strategies
