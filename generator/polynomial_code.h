// C++ code for one orbit's reference polynomial (docs/design.md §11): its coefficients are linear
// combinations of the stencil values, and the strategy decides how the polynomial and its exact
// gradient are written out. The emitter places the result into templates/orbit_<strategy>.fmt.
#pragma once
#include <string>
#include <string_view>

#include "generator/spline_regions.h"

namespace boxgen {

// `monomial`: one coefficient per monomial, then a sum over a table of coordinate powers.
// `horner`: coefficients with stencil values grouped by shared weight, then nested Horner forms
// of the polynomial and of each partial derivative (fewer multiplications; the default).
enum class EmissionStrategy { Monomial, Horner };

// "monomial" | "horner"; anything else: InputError naming the choices.
EmissionStrategy parse_strategy(std::string_view name);
const char* strategy_name(EmissionStrategy s);

// The function `template <class T> T orbit_<orbit>(const T* v, const T* x, T* gradient)`.
std::string orbit_function(const ReferenceRegion& ref, int orbit, int n, int degree, EmissionStrategy strategy);

}  // namespace boxgen
