// The filter metrics (Table 3) against values obtained independently of the code under test.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "analysis/filter_metrics.h"
#include "analysis/quadrature.h"
#include "generator/autocorr.h"
#include "generator/spec.h"

namespace boxgen::analysis {
namespace {

using namespace ::boxgen::generator;  // NOLINT(google-build-using-namespace): the generator's
                                      // lattices and SPECs

FilterMetrics metrics_of(const std::string& preset) {
  const BoxSplineSpec spec = parse_spec(preset);
  return filter_metrics(BoxSplineSpectrum(spec.directions), DualLattice(spec.lattice.generator()),
                        to_double(autocorrelation_refinement(spec).integral_squared));
}

TEST(FilterMetrics, SmoothingAgreesWithThePapersTable3) {
  // Kim 2013, Table 3 prints five decimals of S, computed with Matlab's triplequad: an
  // independent computation. (Its postaliasing digits differ from ours; see the README.)
  EXPECT_NEAR(metrics_of("m12").smoothing, 0.94495, 0.5e-5);
  EXPECT_NEAR(metrics_of("m8").smoothing, 0.85287, 0.5e-5);
  EXPECT_NEAR(metrics_of("m7").smoothing, 0.85488, 0.5e-5);
}

TEST(FilterMetrics, QuadratureConvergesAndTheTwoRulesAgree) {
  for (const char* preset : {"m7", "m8", "m12", "fcc6"}) {
    const FilterMetrics m = metrics_of(preset);
    EXPECT_LT(m.estimated_error, 1e-10) << preset;
    const auto& last = m.steps.back();
    EXPECT_NEAR(last.iterated, last.simplex_fan, 1e-10 * last.iterated) << preset;
  }
}

TEST(FilterMetrics, TricubicOnTheCubeFactorsIntoOneDimensionalIntegrals) {
  // psi_hat = prod_i sinc(w_i/2)^4 and N = [-pi, pi]^3, so ∫_N psi_hat^2 = I^3 with
  // I = ∫_{-pi}^{pi} sinc(t/2)^8 dt, computed here by composite 1-D Gauss-Legendre; and
  // ∫ (M^c)^2 = (∫ B_3^2)^3 = (151/315)^3 for the cubic B-spline B_3 (a textbook value).
  const GaussRule g = gauss_legendre(30);
  double one_d = 0;
  const int pieces = 8;
  for (int p = 0; p < pieces; ++p)
    for (std::size_t k = 0; k < g.nodes.size(); ++k) {
      const double t = -std::numbers::pi + 2 * std::numbers::pi * (p + g.nodes[k]) / pieces;
      one_d +=
          2 * std::numbers::pi / pieces * g.weights[k] * std::pow(std::sin(t / 2) / (t / 2), 8);
    }
  const double volume = std::pow(2 * std::numbers::pi, 3);
  const double expected_s = 1 - std::pow(one_d, 3) / volume;
  const double expected_p =
      (std::pow(2 * std::numbers::pi, 3) * std::pow(151.0 / 315.0, 3) - std::pow(one_d, 3)) /
      volume;
  const FilterMetrics m = metrics_of("tricubic");
  EXPECT_NEAR(m.smoothing, expected_s, 1e-12);
  EXPECT_NEAR(m.postaliasing, expected_p, 1e-12);
}

TEST(FilterMetrics, PostaliasingByParsevalEqualsTheSumOverReplicas) {
  // Independent of a(0): P = (1/|N|) sum_{k != 0} ∫_N psi_hat(w + k)^2, truncated at |k| <= R.
  // The tail beyond R is positive and shrinks with R; for M12 (psi_hat^2 decays like
  // prod sinc^8) R = 6 pi leaves less than 1e-6 of P.
  const BoxSplineSpec spec = parse_spec("m12");
  const BoxSplineSpectrum psi(spec.directions);
  const DualLattice dual(spec.lattice.generator());
  double replicas = 0;
  for (const Vec& k : dual.points_within(6 * std::numbers::pi)) {
    if (k[0] == 0 && k[1] == 0 && k[2] == 0) continue;
    replicas += integrate_iterated(
        dual.cell(),
        [&](const Vec& w) {
          const double p = psi({w[0] + k[0], w[1] + k[1], w[2] + k[2]});
          return p * p;
        },
        24);
  }
  const FilterMetrics m = metrics_of("m12");
  const double direct = replicas / m.nyquist_volume;
  EXPECT_LE(direct, m.postaliasing * (1 + 1e-9));
  EXPECT_NEAR(direct, m.postaliasing, 1e-6 * m.postaliasing);
}

TEST(FilterMetrics, RefusesTooFewOrdersAndMismatchedDimensions) {
  const BoxSplineSpec spec = parse_spec("m7");
  const BoxSplineSpectrum psi(spec.directions);
  const DualLattice dual(spec.lattice.generator());
  EXPECT_THROW(filter_metrics(psi, dual, 0.1, {8}), std::invalid_argument);
  EXPECT_THROW(filter_metrics(BoxSplineSpectrum(IntDirections{{1, 0}, {0, 1}}), dual, 0.1),
               std::invalid_argument);
}

}  // namespace
}  // namespace boxgen::analysis
