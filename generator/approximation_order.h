// The approximation order rho(Xi) of a box spline (docs/design.md §3): the least number of
// columns whose removal leaves a set that does not span R^n. The spline is C^(rho-2) and
// reproduces polynomials of degree < rho; quasi-interpolation prefilters aim at this order.
#pragma once
#include "generator/int_linalg.h"

namespace boxgen::generator {

// rho for the n x m matrix given by its columns, n = 2 or 3. Exact for any integer columns,
// repeated or zero columns included. Returns 0 when the columns do not span R^n at all.
int approximation_order(const IntColumns& xi, int n);

}  // namespace boxgen::generator
