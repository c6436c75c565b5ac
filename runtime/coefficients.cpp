#include "runtime/coefficients.h"

#include <utility>

#include "runtime/prefilter.h"

namespace boxgen::runtime {

template <class T>
LatticeVolume<T> spline_coefficients(LatticeVolume<T> samples, const SplineFilter& f,
                                     PrefilterChoice q, Boundary b, InterpolationReport* report,
                                     bool residual) {
  f.check_lattice(samples.lattice());
  if (!q.is_fir()) {
    InterpolationOptions options;
    options.lambda = q.parameter();
    options.boundary = b;
    options.residual = residual;
    return interpolate(std::move(samples), f, options, report);
  }
  // Enough extension that the prefilter's shrink leaves the reconstruction margin around the
  // samples: required_margin is exactly that sum.
  if (b != Boundary::Strict) samples = extend(samples, f.required_margin(q), b);
  if (q == PrefilterChoice::None) return samples;
  return prefilter(samples, f.prefilter(q));
}

template LatticeVolume<float> spline_coefficients<float>(LatticeVolume<float>, const SplineFilter&,
                                                         PrefilterChoice, Boundary,
                                                         InterpolationReport*, bool);
template LatticeVolume<double> spline_coefficients<double>(LatticeVolume<double>,
                                                           const SplineFilter&, PrefilterChoice,
                                                           Boundary, InterpolationReport*, bool);

}  // namespace boxgen::runtime
