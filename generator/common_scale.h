// Scale invariance (docs/design.md §7, "Scaled matrices"): the directions k Xi on the lattice k G
// give the spline of (Xi, G) stretched by k. With the lattice's normalisation M = |det G| M_Xi,
//   |det kG| M_{k Xi}(x) = |det G| M_Xi(x / k),
// so every region, stencil and basis polynomial of (k Xi, k G) is that of (Xi, G) with x -> x / k
// and lattice points times k. The spline structure is derived on the reduced pair and stretched
// back, so its cost (and the emitted lookup table) does not grow with k.
#pragma once
#include <cstdint>

#include "generator/piecewise_form.h"
#include "generator/spec.h"
#include "generator/spline_regions.h"

namespace boxgen::generator {

// (Xi / k, G / k), k = common_scale(spec) (spec.h) or a divisor of it; the name and text stay the
// user's.
BoxSplineSpec reduced_spec(const BoxSplineSpec& spec, std::int64_t k);
// The pieces of (Xi / k, G / k) from those of (Xi, G): P'(y) = k^n P(k y) on the knot cells
// divided by k, which keep their order (a knot cell index means the same cell in both forms).
PiecewiseForm scaled_down(const PiecewiseForm& form, std::int64_t k);
// The structure of (k Xi, k G) from that of (Xi, G): geometry and lattice points times k, basis
// polynomials B(x / k). The fine cells keep the reduced frame's keys (SplineStructure::scale).
SplineStructure scaled_up(const SplineStructure& s, std::int64_t k);

}  // namespace boxgen::generator
