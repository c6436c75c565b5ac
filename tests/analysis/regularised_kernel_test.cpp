// The error kernel of `boxgen kernel --prefilter interp[:LAMBDA]` describes the runtime's
// interpolation: its prefilter response Q(w), formed from the exact lattice samples by the
// formula conj(S) / (|S|^2 + mu |D|^2), equals the coefficients the runtime computes (coset
// transforms, per-frequency systems, mirror padding) for the samples of a complex exponential
// e^{i w.k}, read at a voxel far from the faces: c(k) = Q(w) e^{i w.k}. Both take D and mu from
// support::regularisation, but the runtime applies them through coset matrices per frequency and
// the kernel through the symbols, and each side passes the basis of L it stores (the runtime a
// Hermite form, the generator the SPEC's G): D must depend on the lattice alone.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <optional>
#include <string>

#include "frontend/analysis_inputs.h"
#include "generator/interpolation_symbol.h"
#include "runtime/interpolation.h"
#include "runtime/spline_filter.h"
#include "tests/analysis/inputs.h"

namespace boxgen::analysis {
namespace {

using runtime::LatticeVolume;
using runtime::SplineFilter;

// Q(w) as the runtime's interpolation applies it: the coefficients of the samples cos(w.k) and
// sin(w.k) at the centre voxel, c_cos + i c_sin = Q(w) e^{i w.k}.
std::complex<double> runtime_response(const SplineFilter& f, std::optional<double> lambda,
                                      const Vec& w, int cells) {
  runtime::InterpolationOptions o;
  o.lambda = lambda;
  o.boundary = runtime::Boundary::Strict;  // the coefficients at the samples, same layout
  const runtime::Sizes sizes{cells, cells, cells};
  LatticeVolume<double> re(f.lattice(), sizes, 1.0, {0, 0, 0});
  LatticeVolume<double> im(f.lattice(), sizes, 1.0, {0, 0, 0});
  for (int c = 0; c < f.lattice().coset_count(); ++c)
    for (int k = 0; k < cells; ++k)
      for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i) {
          const auto p = re.lattice_point(c, i, j, k);
          const double phase = w[0] * static_cast<double>(p[0]) + w[1] * static_cast<double>(p[1]) +
                               w[2] * static_cast<double>(p[2]);
          re(c, i, j, k) = std::cos(phase);
          im(c, i, j, k) = std::sin(phase);
        }
  const int m = cells / 2;
  const auto p = re.lattice_point(0, m, m, m);
  const LatticeVolume<double> cr = runtime::interpolate(re, f, o);
  const LatticeVolume<double> ci = runtime::interpolate(im, f, o);
  const double phase = w[0] * static_cast<double>(p[0]) + w[1] * static_cast<double>(p[1]) +
                       w[2] * static_cast<double>(p[2]);
  return std::complex<double>(cr(0, m, m, m), ci(0, m, m, m)) *
         std::exp(std::complex<double>(0, -phase));
}

// 1 / S(w) from the runtime's own lattice values.
std::complex<double> inverse_symbol(const SplineFilter& f, const Vec& w) {
  std::complex<double> s = 0;
  for (const auto& [k, v] : runtime::lattice_values(f))
    s += v * std::exp(std::complex<double>(0, -(w[0] * k[0] + w[1] * k[1] + w[2] * k[2])));
  return 1.0 / s;
}

struct Case {
  const char* filter;
  const char* prefilter;         // as `boxgen kernel --prefilter` takes it
  std::optional<double> lambda;  // as the runtime takes it
  bool regularised;              // Q differs from 1 / S near the symbol's zeros
};

TEST(RegularisedInterpolation, TheKernelsPrefilterIsTheRuntimesCoefficients) {
  // Low frequencies, and frequencies near the zero of M7's symbol at pi (1, 0, 0), where the
  // regulariser decides Q.
  const Vec low{0.9, 0.5, -0.3}, near_zero{2.9, 0.2, 0.1}, high{2.2, -1.9, 0.6};
  for (const Case& c :
       {Case{"m7", "interp", std::nullopt, true}, Case{"m7", "interp:0.01", 0.01, true},
        Case{"m12", "interp", std::nullopt, true}, Case{"m8", "interp", std::nullopt, false},
        Case{"m8", "interp:0.01", 0.01, true}}) {
    const generator::BoxSplineSpec spec = generator::parse_spec(c.filter);
    const ErrorKernel e = frontend::interpolation_kernel(
        spec, c.filter, test::autocorrelation_taps(spec), c.prefilter);
    const SplineFilter f = SplineFilter::parse(c.filter);
    // The faces' influence at the centre: within this margin the inverse filter has fallen below
    // 1e-6 of its peak; summed over the faces it leaves up to 1.1e-5 of the data (measured: m12
    // near the zero, where |Q| = 0.11), hence the tolerance 5e-5 max(1, |Q|).
    const int cells = 2 * runtime::interpolation_margin(f, c.lambda) + 3;
    for (const Vec& w : {low, near_zero, high}) {
      const std::complex<long double> q = e.prefilter_response(w);
      const std::complex<double> expected(static_cast<double>(q.real()),
                                          static_cast<double>(q.imag()));
      const std::complex<double> measured = runtime_response(f, c.lambda, w, cells);
      const std::string at = std::string(c.filter) + " " + c.prefilter + " at w = (" +
                             std::to_string(w[0]) + "," + std::to_string(w[1]) + "," +
                             std::to_string(w[2]) + ")";
      EXPECT_LE(std::abs(measured - expected), 5e-5 * std::max(1.0, std::abs(expected))) << at;
      // Without the regulariser the kernel would use 1 / S: the comparison tells them apart.
      if (c.regularised && w[0] == near_zero[0]) {
        EXPECT_GT(std::abs(inverse_symbol(f, w) - expected), 1e-2 * std::abs(expected)) << at;
      }
      if (!c.regularised) {
        EXPECT_LE(std::abs(inverse_symbol(f, w) - expected), 1e-9 * std::abs(expected)) << at;
      }
    }
  }
}

}  // namespace
}  // namespace boxgen::analysis
