// The free parameters of a quasi-interpolation prefilter chosen to minimise the integrated error
// kernel over the Nyquist region N (docs/design.md §19; the optimised prefilters q1opt, q2opt).
// For a symmetric prefilter Q(w) = sum_j q(j) cos(w.j) the error kernel of §10 integrates to
//   (1/|N|) ∫_N E(w) dw = 1 + q^T G q - 2 b^T q,
//   G(j, k) = |det G| a(j - k)           (exact: the autocorrelation samples; orthogonality of
//                                          e^{-i w.j} over N),
//   b(j)    = (1/|N|) ∫_N psi_hat(w) cos(w.j) dw   (quadrature, analysis/quadrature.h),
// because ∫_N (1 - psi_hat^2 / A) + ∫_N psi_hat^2 / A = |N|. On the family of prefilters of full
// order, q = particular + sum_i t_i basis_i (generator/prefilter.h, converted to double), this is
// a quadratic in t, minimised by one small linear system.
#pragma once
#include <cstdint>
#include <vector>

#include "analysis/dual_lattice.h"
#include "analysis/error_kernel.h"
#include "analysis/spectrum.h"

namespace boxgen::analysis {

// The family in the plain numbers the analysis takes: weights per orbit.
struct PrefilterFamilyValues {
  std::vector<std::vector<std::vector<std::int64_t>>> orbits;  // the points of each orbit
  std::vector<double> particular;                              // one weight per orbit
  std::vector<std::vector<double>> basis;                      // one weight vector per parameter
};

struct OptimisedParameters {
  std::vector<double> parameters;  // t
  double at_zero = 0;              // (1/|N|) ∫_N E dw with t = 0 (the parameters set to zero)
  double optimised = 0;            // the same at t
  // Largest change of any (1/|N|) b(orbit) between the two quadrature orders: the order of the
  // quadrature error in the objective per unit weight.
  double quadrature_change = 0;
};

inline const std::vector<int> kOptimalPrefilterOrders = {16, 24};

// Throws std::invalid_argument for an empty family, a missing autocorrelation sample or a singular
// system (parameters the objective does not see).
OptimisedParameters minimise_integrated_error(
    const BoxSplineSpectrum& psi, const DualLattice& dual,
    const std::vector<LatticeTap>& autocorrelation, const PrefilterFamilyValues& family,
    const std::vector<int>& orders = kOptimalPrefilterOrders);

}  // namespace boxgen::analysis
