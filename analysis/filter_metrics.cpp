#include "analysis/filter_metrics.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "analysis/quadrature.h"

namespace boxgen::analysis {

FilterMetrics filter_metrics(const BoxSplineSpectrum& psi, const DualLattice& dual,
                             double integral_squared, const std::vector<int>& orders) {
  if (orders.size() < 2)
    throw std::invalid_argument("the metrics need at least two quadrature orders");
  if (psi.dimension() != dual.dimension())
    throw std::invalid_argument("filter and lattice dimensions differ");
  const Integrand f = [&](const Vec& w) {
    const double p = psi(w);
    return p * p;
  };
  FilterMetrics m;
  for (int order : orders)
    m.steps.push_back({order, integrate_iterated(dual.cell(), f, order),
                       integrate_simplex_fan(dual.cell(), f, order)});
  m.nyquist_volume = std::pow(2 * std::numbers::pi, dual.dimension()) / dual.det_g();
  m.inside = m.steps.back().iterated;
  m.total = std::pow(2 * std::numbers::pi, dual.dimension()) * integral_squared;
  const auto& last = m.steps.back();
  const auto& before = m.steps[m.steps.size() - 2];
  m.estimated_error = std::max({std::abs(last.iterated - before.iterated),
                                std::abs(last.simplex_fan - before.simplex_fan),
                                std::abs(last.iterated - last.simplex_fan)}) /
                      m.nyquist_volume;
  m.smoothing = 1 - m.inside / m.nyquist_volume;
  m.postaliasing = (m.total - m.inside) / m.nyquist_volume;
  return m;
}

}  // namespace boxgen::analysis
