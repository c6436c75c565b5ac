// From samples to the coefficients a filter's spline is evaluated on: the one step every command,
// the Python module and the GL device take after reading a volume (docs/runtime.md).
//
//   none, q1, q2   the volume extended beyond its faces by boundary b (boundary.h) far enough
//                  that, after the FIR prefilter's shrink (prefilter.h), every point of the
//                  sampled box evaluates; strict: not extended (today's refusal near the faces)
//   interp[:L]     interpolation (interpolation.h) with the same boundary
//
//   LatticeVolume<double> c = spline_coefficients(std::move(samples), f,
//   PrefilterChoice::interp()); const Reconstructor<double> spline(c, f);
#pragma once
#include "runtime/boundary.h"
#include "runtime/interpolation.h"
#include "runtime/lattice_volume.h"
#include "runtime/prefilter_choice.h"
#include "runtime/spline_filter.h"

namespace boxgen::runtime {

// The coefficients of f for `samples` after prefilter q under boundary b. report (may be null):
// filled for interp (and left alone otherwise); residual: also compute interp's residual at the
// samples (always done where interp regularises). Throws as prefilter() and interpolate(), and
// std::invalid_argument (one line) for a volume of another lattice than f's.
template <class T>
LatticeVolume<T> spline_coefficients(LatticeVolume<T> samples, const SplineFilter& f,
                                     PrefilterChoice q, Boundary b = kDefaultBoundary,
                                     InterpolationReport* report = nullptr, bool residual = false);

extern template LatticeVolume<float> spline_coefficients<float>(LatticeVolume<float>,
                                                                const SplineFilter&,
                                                                PrefilterChoice, Boundary,
                                                                InterpolationReport*, bool);
extern template LatticeVolume<double> spline_coefficients<double>(LatticeVolume<double>,
                                                                  const SplineFilter&,
                                                                  PrefilterChoice, Boundary,
                                                                  InterpolationReport*, bool);

}  // namespace boxgen::runtime
