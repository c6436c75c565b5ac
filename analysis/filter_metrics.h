// Marschner-Lobb filter metrics of psi = M^c on its lattice (docs/design.md §10; the paper's
// Table 3):
//   smoothing     S = 1 - (1/|N|) ∫_N |psi_hat|^2,
//   postaliasing  P = (1/|N|) ∫_{outside N} |psi_hat|^2 = (1/|N|) ((2 pi)^n a(0) - ∫_N
//   |psi_hat|^2),
// the unbounded integral by Parseval from the exact a(0) = ∫ (M^c)^2 (the generator's
// autocorrelation), the bounded one by quadrature over the Nyquist region N at rising orders.
#pragma once
#include <vector>

#include "analysis/dual_lattice.h"
#include "analysis/spectrum.h"

namespace boxgen::analysis {

struct QuadratureStep {
  int order = 0;
  double iterated = 0;     // ∫_N |psi_hat|^2 by the iterated rule
  double simplex_fan = 0;  // the same by the simplex-fan rule
};

struct FilterMetrics {
  double smoothing = 0, postaliasing = 0;
  double nyquist_volume = 0;  // |N|
  double inside = 0;          // ∫_N |psi_hat|^2 (iterated rule, highest order)
  double total = 0;           // (2 pi)^n a(0)
  // Largest change of the inside integral between the two highest orders and between the two
  // rules there, relative to |N|: a bound on the error of S and P as the steps show it.
  double estimated_error = 0;
  std::vector<QuadratureStep> steps;
};

inline const std::vector<int> kDefaultMetricOrders = {4, 8, 16, 24, 32};

FilterMetrics filter_metrics(const BoxSplineSpectrum& psi, const DualLattice& dual,
                             double integral_squared,
                             const std::vector<int>& orders = kDefaultMetricOrders);

}  // namespace boxgen::analysis
