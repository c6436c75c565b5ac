// qfir:K on any filter (docs/design.md §18): the FIR interpolation prefilter on the lattice
// shells 0..K (shell k: the lattice points of the k-th smallest norm), the taps of
// support/fir_prefilter.hpp solved in double from the filter's own values at the lattice points
// (lattice_values, interpolation.h). So it needs nothing from the generator and works for every
// FilterSource: the registry, a SPEC compiled at run time, a user's header. `boxgen prefilter
// SPEC --prefilter qfir:K` prints the same weights exactly; a test compares the two.
#pragma once
#include "runtime/prefilter.h"
#include "runtime/spline_filter.h"

namespace boxgen::runtime {

// The largest K of qfir:K (the generator's kMaxPrefilterShell).
inline constexpr int kMaxFirShell = 8;

// The taps of qfir:K. Throws std::invalid_argument (one line) for K outside 0..kMaxFirShell or
// when no prefilter of the filter's approximation order lies on those shells.
PrefilterTaps fir_interpolation_taps(const SplineFilter& f, int last_shell);

}  // namespace boxgen::runtime
