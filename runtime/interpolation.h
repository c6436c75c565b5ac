// Interpolation: the coefficients c of a filter's spline s(x) = sum_j c(j) M(x - j) (j in the
// lattice L) that pass through every sample, s(k) = V(k), for any filter on any lattice
// (docs/runtime.md, "Interpolation and boundaries"; docs/design.md §17).
//
// On L = union of K cosets off_a + d Z^3 the conditions are, per coset pair (a, b), convolutions
// on d Z^3 with the kernels h_ab(t) = M(d t + off_a - off_b); a discrete Fourier transform over the
// coset grid turns them into one K x K system H(w) c(w) = V(w) per frequency. The volume is
// extended by `padding` coset cells per side (boundary.h: mirror or clamp) and transformed
// periodically (FFTW, real-to-complex, on batch_threads() threads): every sample, and every
// padding value, is reproduced whatever the padding holds; the padding only shapes the spline
// near the faces, and its width follows the decay of the inverse filter.
//
// Where the filter's symbol A(w) = sum_k M(k) exp(-i w.k) vanishes (M7: its shifts are linearly
// dependent) exact interpolation is ill posed; there the coefficients are the Tikhonov-regularised
// solution c = (H* H + mu I)^-1 H* V, mu = lambda max|A|^2, which leaves a residual at the samples
// (reported). M(k) comes from the filter's own evaluator (the spline of a delta volume at the
// lattice points, in double), so this works for every FilterSource, a user's header included.
#pragma once
#include <cmath>
#include <limits>
#include <optional>

#include "runtime/boundary.h"
#include "runtime/lattice_volume.h"
#include "runtime/prefilter.h"
#include "runtime/spline_filter.h"
#include "support/lattice_regulariser.h"

namespace boxgen::runtime {

// The filter's values M(k) at the lattice points k where they are not zero (|M(k)| > 1e-13
// max |M|), as taps: prefilter(c, lattice_values(f)) is the spline of coefficients c at the
// samples. From the evaluator of f in double (about 1e-16 relative).
PrefilterTaps lattice_values(const SplineFilter& f);

// The smallest and largest |A(w)| over the grid w = 2 pi (i, j, k) / 64 (lattice coordinates:
// A has period 2 pi along each axis), which holds the zeros of the registry's filters; where
// min |A| < kVanishing max |A| the symbol is taken to vanish: interp then regularises with
// lambda = kDefaultLambda unless told otherwise (and refuses lambda = 0). One implementation with
// boxgen's error kernel (support/lattice_regulariser.h).
using support::symbol_bounds;
using support::SymbolBounds;
inline constexpr double kVanishing = support::kVanishing;
inline constexpr double kDefaultLambda = support::kDefaultLambda;
// Largest K (cosets of d Z^3) interpolation takes: each frequency solves a K x K system (BCC 2,
// FCC 4; a custom lattice of period d up to d^3 / |det G|).
inline constexpr int kMaxInterpolationCosets = 32;

struct InterpolationOptions {
  // Tikhonov weight relative to max |A|^2, in [0, 1]; none: 0 where the symbol does not vanish,
  // kDefaultLambda where it does.
  std::optional<double> lambda;
  // mirror, clamp: the result extends the samples by the reconstruction margin of f, so that
  // every point of the sampled box evaluates; strict: the result holds the coefficients at the
  // samples only (the transform still pads with mirror, or clamp where mirror does not apply).
  Boundary boundary = kDefaultBoundary;
  // Compute the residual at the samples (always done when lambda > 0).
  bool residual = false;
};

struct InterpolationReport {
  double lambda = 0;    // the Tikhonov weight used, relative to max |A|^2 (0: exact)
  SymbolBounds symbol;  // of the filter
  int padding = 0;      // coset cells of extension per side before the transform (at least)
  Sizes transform{};    // transform size per coset and axis
  Boundary extension = Boundary::Mirror;  // how the transform's padding was filled
  int margin = 0;  // coset cells of coefficients kept beyond the samples per side
  // max |s(k) - V(k)| and the RMS of s(k) - V(k) over the samples, both relative to max |V(k)|;
  // NaN when not computed.
  double residual_max = std::numeric_limits<double>::quiet_NaN();
  double residual_rms = std::numeric_limits<double>::quiet_NaN();
};

// The interpolating (or regularised) coefficients of f for `samples`. Throws
// std::invalid_argument (one line) for a volume of another lattice, a lattice of more than
// kMaxInterpolationCosets cosets, a volume with fewer than 2 samples per coset along an axis,
// lambda not finite or outside [0, 1], lambda = 0 where the symbol vanishes, or a transform beyond
// LatticeVolume's limits; std::bad_alloc when memory runs out. Computes in double whatever T is.
// Coset cells of samples to take beyond a region of interest so that the faces' influence on the
// interpolating coefficients has decayed below 1e-6 of the data there (with the reconstruction
// margin of f): SplineFilter::required_margin(interp). The same arguments as interpolate.
int interpolation_margin(const SplineFilter& f, std::optional<double> lambda);

// The samples are taken by value: pass them with std::move to let their memory go back before
// the transforms (unless the residual is computed).
template <class T>
LatticeVolume<T> interpolate(LatticeVolume<T> samples, const SplineFilter& f,
                             const InterpolationOptions& options = {},
                             InterpolationReport* report = nullptr);

extern template LatticeVolume<float> interpolate<float>(LatticeVolume<float>, const SplineFilter&,
                                                        const InterpolationOptions&,
                                                        InterpolationReport*);
extern template LatticeVolume<double> interpolate<double>(LatticeVolume<double>,
                                                          const SplineFilter&,
                                                          const InterpolationOptions&,
                                                          InterpolationReport*);

}  // namespace boxgen::runtime
