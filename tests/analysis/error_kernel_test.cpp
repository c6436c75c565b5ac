// The Blu-Unser error kernel: A(w) from the exact autocorrelation samples against the truncated
// sum over the dual lattice, the slopes at w -> 0 that the approximation orders predict, and the
// orderings the paper reports for Fig. 13, as measured.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "analysis/error_kernel.h"
#include "generator/interpolation_symbol.h"
#include "tests/analysis/inputs.h"

namespace boxgen::analysis {
namespace {

using namespace ::boxgen::generator;  // NOLINT(google-build-using-namespace): the generator's
                                      // lattices and SPECs

ErrorKernel kernel_of(const BoxSplineSpec& spec, const std::vector<int>& shells) {
  return ErrorKernel(
      BoxSplineSpectrum(spec.directions), static_cast<double>(spec.lattice.det_abs()),
      test::autocorrelation_taps(spec),
      shells.empty() ? std::vector<LatticeTap>{} : test::prefilter_taps(spec, shells));
}

Vec along(const Vec& d, double w) { return {w * d[0], w * d[1], w * d[2]}; }

TEST(ErrorKernel, DtftOfTheExactAutocorrelationEqualsTheTruncatedDualLatticeSum) {
  for (const char* preset : {"m7", "m8", "m12", "fcc6", "tricubic"}) {
    const BoxSplineSpec spec = parse_spec(preset);
    const ErrorKernel e = kernel_of(spec, {});
    const DualLattice dual(spec.lattice.generator());
    for (const Vec& w : {Vec{0.3, 0.1, -0.2}, Vec{1.0, 1.0, 1.0}, Vec{2.5, 0.0, 0.4}}) {
      const long double exact = e.aliasing_sum(w);
      const long double direct =
          aliasing_sum_direct(BoxSplineSpectrum(spec.directions), dual, w, 40 * std::numbers::pi);
      // The truncated sum misses a positive tail, which bounds the difference from above.
      EXPECT_NEAR(static_cast<double>(direct), static_cast<double>(exact),
                  2e-6 * static_cast<double>(exact))
          << preset << " at (" << w[0] << "," << w[1] << "," << w[2] << ")";
      EXPECT_LE(static_cast<double>(direct), static_cast<double>(exact) * (1 + 1e-12)) << preset;
    }
  }
}

// Slope of log E between w and 2w along (1,1,1).
double slope(const ErrorKernel& e, double w, bool minimum = false) {
  const Vec d{1, 1, 1};
  const long double a = minimum ? e.minimum(along(d, w)) : e(along(d, w));
  const long double b = minimum ? e.minimum(along(d, 2 * w)) : e(along(d, 2 * w));
  return static_cast<double>(std::log(b / a) / std::log(2.0L));
}

// E = O(|w|^(2 rho)) for a prefilter of order rho (Blu-Unser): rho = 4 for M7, M8, M12 and the
// tricubic, so |w|^8; without a prefilter the samples reproduce only constants and linears
// (rho = 2), so |w|^4. fcc6 is cubic: its prefilters reach rho = 3, so |w|^6.
TEST(ErrorKernel, FallsLikeW8WithAPrefilterAndW4Without) {
  for (const char* preset : {"m7", "m8", "m12", "tricubic", "fcc6"}) {
    const BoxSplineSpec spec = parse_spec(preset);
    EXPECT_NEAR(slope(kernel_of(spec, {}), 0.02), 4.0, 0.05) << preset << " without prefilter";
    const double expected = std::string(preset) == "fcc6" ? 6.0 : 8.0;
    EXPECT_EQ(derive_prefilter(spec, {0, 1}).order * 2, static_cast<int>(expected)) << preset;
    EXPECT_NEAR(slope(kernel_of(spec, {0, 1}), 0.02), expected, 0.1) << preset << " with q1";
    EXPECT_NEAR(slope(kernel_of(spec, {0, 1, 2}), 0.02), expected, 0.1) << preset << " with q2";
  }
}

TEST(ErrorKernel, VanishesAtZeroAndNeverFallsBelowTheMinimum) {
  const BoxSplineSpec spec = parse_spec("m7");
  const ErrorKernel e = kernel_of(spec, {0, 1, 2});
  EXPECT_NEAR(static_cast<double>(e({0, 0, 0})), 0, 1e-15);
  for (double w = 0.05; w < std::numbers::pi; w += 0.05) {
    const Vec p{w, 0.7 * w, -0.3 * w};
    EXPECT_GE(e(p), e.minimum(p) - 1e-15L);
    EXPECT_GE(e.minimum(p), -1e-15L);
  }
}

// The paper (section 5.5): E_min of M12 < M8 < M7, and with each prefilter M7's kernel is below
// M8's. Measured along (1,1,1) on the band of Fig. 13 (0, pi/2].
TEST(ErrorKernel, PapersOrderingsHoldOnTheBandOfFig13) {
  const BoxSplineSpec m7 = parse_spec("m7"), m8 = parse_spec("m8"), m12 = parse_spec("m12");
  const Vec d{1, 1, 1};
  for (const std::vector<int>& shells :
       {std::vector<int>{}, std::vector<int>{0, 1}, std::vector<int>{0, 1, 2}}) {
    const ErrorKernel e7 = kernel_of(m7, shells), e8 = kernel_of(m8, shells),
                      e12 = kernel_of(m12, shells);
    for (double w = 0.05; w <= std::numbers::pi / 2; w += 0.05) {
      EXPECT_LT(e7(along(d, w)), e8(along(d, w))) << "w " << w << " shells " << shells.size();
      if (shells.empty()) {
        EXPECT_LT(e12.minimum(along(d, w)), e8.minimum(along(d, w))) << w;
        EXPECT_LT(e8.minimum(along(d, w)), e7.minimum(along(d, w))) << w;
      }
    }
  }
}

ErrorKernel interpolation_kernel_of(const BoxSplineSpec& spec) {
  std::vector<LatticeTap> samples;
  for (const auto& s : lattice_samples(spec)) samples.push_back({s.point, to_double(s.value)});
  return ErrorKernel::interpolation(BoxSplineSpectrum(spec.directions),
                                    static_cast<double>(spec.lattice.det_abs()),
                                    test::autocorrelation_taps(spec), std::move(samples));
}

// Interpolation's Q = 1 / S: for the tricubic B-spline S(w) = prod_i (2 + cos w_i) / 3 by hand
// (its values 2/3 at 0 and 1/6 at +-1 per axis), so E = E_min + A (1/S - psi_hat/A)^2.
TEST(ErrorKernel, InterpolationUsesTheInverseSymbol) {
  const BoxSplineSpec spec = parse_spec("tricubic");
  const ErrorKernel e = interpolation_kernel_of(spec);
  const BoxSplineSpectrum psi(spec.directions);
  for (const Vec& w : {Vec{0.3, 0.1, -0.2}, Vec{1.0, 1.0, 1.0}, Vec{2.5, 0.0, 0.4}}) {
    const long double s = (2 + std::cos(w[0])) * (2 + std::cos(w[1])) * (2 + std::cos(w[2])) / 27;
    const long double a = e.aliasing_sum(w), p = psi.precise(w);
    const long double expected = e.minimum(w) + a * (1 / s - p / a) * (1 / s - p / a);
    EXPECT_NEAR(static_cast<double>(e(w)), static_cast<double>(expected), 1e-13)
        << w[0] << "," << w[1] << "," << w[2];
  }
}

// Interpolation keeps the order 4 of M8 and the tricubic (|w|^8), and lies above E_min.
TEST(ErrorKernel, InterpolationFallsLikeW8AndNeverBelowTheMinimum) {
  for (const char* preset : {"m8", "tricubic"}) {
    const ErrorKernel e = interpolation_kernel_of(parse_spec(preset));
    EXPECT_NEAR(slope(e, 0.08), 8.0, 0.1) << preset;  // at 0.02 E is below long double's floor
    for (double w = 0.05; w < std::numbers::pi; w += 0.05) {
      const Vec p{w, 0.7 * w, -0.3 * w};
      EXPECT_GE(e(p), e.minimum(p) - 1e-15L) << preset << " " << w;
    }
  }
}

}  // namespace
}  // namespace boxgen::analysis
