// The bridge from the exact generator to the floating-point analysis (analysis/): a SPEC's
// directions and lattice, its exact autocorrelation samples and prefilter taps, converted to
// double once, here.
#pragma once
#include <string>
#include <vector>

#include "analysis/dual_lattice.h"
#include "analysis/error_kernel.h"
#include "analysis/spectrum.h"
#include "generator/autocorr.h"
#include "generator/spec.h"

namespace boxgen::frontend {

using namespace ::boxgen::generator;  // NOLINT(google-build-using-namespace): the generator's front
                                      // end

analysis::BoxSplineSpectrum spectrum_of(const BoxSplineSpec& spec);
// --equal-density: the factor a = |det G|^(-1/n) by which the SPEC's frequencies are scaled so
// that lattices compare at one sample per unit volume (the lattice a G, the filter M(x / a),
// whose transform at w is psi_hat(a w)); 1 when `equal` is false.
double density_scale(const BoxSplineSpec& spec, bool equal);
analysis::DualLattice dual_of(const BoxSplineSpec& spec);
std::vector<analysis::LatticeTap> taps_of(const Autocorrelation& a);
// "none" -> empty; q1, q2, q1opt, q2opt or qfir:K -> its taps (generator/prefilter.h). Throws
// InputError otherwise ("min", "interp" and "interp:LAMBDA" are handled by the caller).
std::vector<analysis::LatticeTap> prefilter_taps_of(const BoxSplineSpec& spec,
                                                    const std::string& name);

// "interp" or "interp:LAMBDA": the runtime's interpolation (docs/design.md §17).
bool is_interpolation(const std::string& prefilter);
// The error kernel of that interpolation of the filter `name`: Q = conj(S) / (|S|^2 + mu |D|^2),
// S the interpolation symbol of the exact lattice samples, with the runtime's lambda (LAMBDA, or
// by default 0 where S does not vanish and 1e-3 where it does), D and mu: one implementation,
// support::regularisation. Throws InputError (one line) for a LAMBDA that is not a number in
// [0, 1], or 0 where S vanishes.
analysis::ErrorKernel interpolation_kernel(const BoxSplineSpec& spec, const std::string& name,
                                           const std::vector<analysis::LatticeTap>& autocorrelation,
                                           const std::string& prefilter);

}  // namespace boxgen::frontend
