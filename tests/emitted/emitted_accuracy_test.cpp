// Emitted evaluators (value, gradient and Hessian; double and float; the value-only, gradient
// and Hessian paths each) against the exact rational spline
// s(x) = sum_j V(j) M(x - j) computed from the generator's piecewise form (cell lookup by key,
// not the emitted tables), at 1000 points per matrix, half of them within 1e-3 of a knot plane.
// Points are dyadic (multiples of 2^-20, |x| < 4), so float and double hold them exactly and the
// comparison is with the exact value at the very point evaluated. V is an integer hash, so every
// stencil weight matters. Tolerances, relative to max|V| = 1000: double 1e-13, float 2e-6 (value
// and gradient); second derivatives, whose coefficients carry one more power of the degree, 4x
// that. Hessians are compared only for C^2 splines and, for the others (zp), away from knot planes
// where they jump. The sanitizer build (BOXGEN_SANITIZE) checks 250 of the same points: it looks
// for memory and undefined-behaviour errors, which the first points exercise as well, and the
// exact sums would otherwise take minutes there; the optimised build checks all 1000.
#include <gtest/gtest.h>

#ifndef BOXGEN_EXACT_POINTS
#define BOXGEN_EXACT_POINTS 1000
#endif

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <random>
#include <sstream>

#include "emitted/biquadratic.hpp"
#include "emitted/cart7.hpp"
#include "emitted/cart7_shifted.hpp"
#include "emitted/fcc6.hpp"
#include "emitted/fcc6_bernstein.hpp"
#include "emitted/fcc6_shifted.hpp"
#include "emitted/m12_horner.hpp"
#include "emitted/m12_shifted.hpp"
#include "emitted/m7_bernstein.hpp"
#include "emitted/m7_doubled.hpp"
#include "emitted/m7_horner.hpp"
#include "emitted/m7_monomial.hpp"
#include "emitted/m8_bernstein.hpp"
#include "emitted/m8_horner.hpp"
#include "emitted/tricubic.hpp"
#include "emitted/tricubic_horner.hpp"
#include "emitted/zp.hpp"
#include "emitted/zp_bernstein.hpp"
#include "emitted/zp_monomial.hpp"
#include "emitted/zp_shifted.hpp"
#include "emitted/zp_tripled.hpp"
#include "generated/m12.hpp"
#include "generated/m7.hpp"
#include "generated/m8.hpp"
#include "runtime/reconstruction.h"
#include "tests/emitted/exact_reference.h"

namespace boxgen::generator {
namespace {

using namespace exact_reference;  // NOLINT(google-build-using-namespace): the shared oracle

// The exact values at the test points of one matrix (and lattice), computed once for every header
// emitted from it: the exact sums dominate these tests' time (M12: a few seconds per 100 points).
struct Truth {
  explicit Truth(const std::string& preset, const std::string& lattice = "")
      : ref(preset, lattice), points(test_points(ref, BOXGEN_EXACT_POINTS)) {
    for (const auto& x : points) exact.push_back(ref.at(x));
  }
  Reference ref;
  std::vector<RatVec> points;
  std::vector<Exact> exact;
};

// One emitted header (`name`) in T against the truth.
template <class T, int N, class Evaluate>
void check_filter(const Truth& truth, const char* name, Evaluate evaluate, double tolerance) {
  ASSERT_EQ(truth.ref.dimension(), N);
  constexpr int H = N * (N + 1) / 2;
  const bool c2 = truth.ref.twice_differentiable();
  const std::string what = std::string(name) + (sizeof(T) == 4 ? " float" : " double");
  double worst = 0, worst_gradient = 0, worst_hessian = 0;
  int hessians_compared = 0;
  for (std::size_t p = 0; p < truth.points.size(); ++p) {
    const RatVec& x = truth.points[p];
    const Exact& e = truth.exact[p];
    std::array<T, N> xt;
    for (int i = 0; i < N; ++i) xt[i] = static_cast<T>(to_double(x[i]));
    for (int i = 0; i < N; ++i)
      ASSERT_EQ(exact_rational(static_cast<double>(xt[i])), x[i]) << "not representable";
    // The three paths: value only, value + gradient, value + gradient + Hessian.
    std::array<T, N> g, g2;
    std::array<T, H> h;
    const T v0 = evaluate(xt, nullptr, nullptr);
    const T v1 = evaluate(xt, &g, nullptr);
    const T v2 = evaluate(xt, &g2, &h);
    for (const T v : {v0, v1, v2})
      worst = std::max(worst, std::abs(static_cast<double>(v) - to_double(e.value)));
    for (int d = 0; d < N; ++d)
      for (const T gd : {g[d], g2[d]})
        worst_gradient =
            std::max(worst_gradient, std::abs(static_cast<double>(gd) - to_double(e.gradient[d])));
    if (!c2 && !e.hessian_defined) continue;
    ++hessians_compared;
    for (int k = 0; k < H; ++k)
      worst_hessian =
          std::max(worst_hessian, std::abs(static_cast<double>(h[k]) - to_double(e.hessian[k])));
  }
  EXPECT_LE(worst / kMaxV, tolerance) << what << " value";
  EXPECT_LE(worst_gradient / kMaxV, tolerance) << what << " gradient";
  EXPECT_LE(worst_hessian / kMaxV, 4 * tolerance) << what << " hessian";
  EXPECT_GE(hessians_compared, BOXGEN_EXACT_POINTS / 2) << what;
  // In scientific notation (std::to_string's six decimals print every error here as 0).
  auto scientific = [](double e) {
    std::ostringstream out;
    out << std::scientific << std::setprecision(2) << e;
    return out.str();
  };
  std::string key = what;
  std::replace(key.begin(), key.end(), ' ', '_');
  ::testing::Test::RecordProperty(key + "_max_relative_error", scientific(worst / kMaxV));
  ::testing::Test::RecordProperty(key + "_max_relative_gradient_error",
                                  scientific(worst_gradient / kMaxV));
  ::testing::Test::RecordProperty(key + "_max_relative_hessian_error",
                                  scientific(worst_hessian / kMaxV));
}

template <class T, std::size_t N>
using HessianOf = std::array<T, N*(N + 1) / 2>;

// The header generated::NS in double (1e-13) and in float (2e-6) against the truth.
#define BOXGEN_CHECK_EMITTED_AS(T, NS, TRUTH, N, TOLERANCE)                                       \
  check_filter<T, N>(                                                                             \
      TRUTH, #NS,                                                                                 \
      [](const std::array<T, N>& x, std::array<T, N>* g, HessianOf<T, N>* h) {                    \
        return generated::NS::evaluate<T>(                                                        \
            x,                                                                                    \
            [](const generated::NS::Point& j) { return data_value(IntVec(j.begin(), j.end())); }, \
            g, h);                                                                                \
      },                                                                                          \
      TOLERANCE)
#define BOXGEN_CHECK_EMITTED(NS, TRUTH, N)                \
  do {                                                    \
    BOXGEN_CHECK_EMITTED_AS(double, NS, TRUTH, N, 1e-13); \
    BOXGEN_CHECK_EMITTED_AS(float, NS, TRUTH, N, 2e-6);   \
  } while (false)

// The same comparison through the runtime's batch API, Reconstructor<T>::evaluate (the SIMD batch
// path, runtime/simd_batch.h, where the CPU has one), all points in one call (a partial last
// chunk): a BCC volume holds V(j) at lattice point j + S (S even keeps the parity), with spacing 1
// and origin -S, so world point x is the generator's point x, exactly.
template <class T>
void check_batch(const Truth& truth, const runtime::SplineFilter& filter, double tolerance) {
  constexpr int kOffset = 10, kSize = 12;  // points |x| < 4, reach <= 4: inside [0, 2 kSize - 1]
  runtime::LatticeVolume<T> volume(runtime::CosetLattice::bcc(), {kSize, kSize, kSize}, 1.0,
                                   {-kOffset, -kOffset, -kOffset});
  for (int c = 0; c < 2; ++c)
    for (int k = 0; k < kSize; ++k)
      for (int j = 0; j < kSize; ++j)
        for (int i = 0; i < kSize; ++i)
          volume(c, i, j, k) = static_cast<T>(
              data_value({2 * i + c - kOffset, 2 * j + c - kOffset, 2 * k + c - kOffset}));
  std::vector<runtime::Vec3> points;
  for (const auto& x : truth.points)
    points.push_back({to_double(x[0]), to_double(x[1]), to_double(x[2])});
  std::vector<T> values(points.size());
  std::vector<runtime::Vec3> gradients(points.size());
  std::vector<runtime::Hessian> hessians(points.size());
  runtime::Reconstructor<T>(volume, filter).evaluate(points, values, gradients, hessians);
  const bool c2 = truth.ref.twice_differentiable();
  double worst = 0, worst_gradient = 0, worst_hessian = 0;
  for (std::size_t p = 0; p < points.size(); ++p) {
    const Exact& e = truth.exact[p];
    worst = std::max(worst, std::abs(static_cast<double>(values[p]) - to_double(e.value)));
    for (int d = 0; d < 3; ++d)
      worst_gradient =
          std::max(worst_gradient, std::abs(gradients[p][d] - to_double(e.gradient[d])));
    if (!c2 && !e.hessian_defined) continue;
    for (int k = 0; k < 6; ++k)
      worst_hessian = std::max(worst_hessian, std::abs(hessians[p][k] - to_double(e.hessian[k])));
  }
  const char* type = sizeof(T) == 4 ? "batch float" : "batch double";
  EXPECT_LE(worst / kMaxV, tolerance) << type << " value";
  EXPECT_LE(worst_gradient / kMaxV, tolerance) << type << " gradient";
  EXPECT_LE(worst_hessian / kMaxV, 4 * tolerance) << type << " hessian";
}

void check_batch(const Truth& truth, const std::string& preset) {
  const runtime::SplineFilter filter = runtime::SplineFilter::parse(preset);
  check_batch<double>(truth, filter, 1e-13);
  check_batch<float>(truth, filter, 2e-6);
}

// One test per matrix: every header emitted from it (each strategy), then, for the registry's
// BCC filters, the runtime's batch path.
TEST(Emitted, M7) {
  const Truth truth("m7");
  BOXGEN_CHECK_EMITTED(m7, truth, 3);
  BOXGEN_CHECK_EMITTED(m7_horner, truth, 3);
  BOXGEN_CHECK_EMITTED(m7_monomial, truth, 3);
  BOXGEN_CHECK_EMITTED(m7_bernstein, truth, 3);
  check_batch(truth, "m7");
}
TEST(Emitted, M8) {
  const Truth truth("m8");
  BOXGEN_CHECK_EMITTED(m8, truth, 3);
  BOXGEN_CHECK_EMITTED(m8_horner, truth, 3);
  BOXGEN_CHECK_EMITTED(m8_bernstein, truth, 3);
  check_batch(truth, "m8");
}
TEST(Emitted, M12) {
  const Truth truth("m12");
  BOXGEN_CHECK_EMITTED(m12, truth, 3);
  BOXGEN_CHECK_EMITTED(m12_horner, truth, 3);
  BOXGEN_CHECK_EMITTED(m12_shifted, truth, 3);
  check_batch(truth, "m12");
}
TEST(Emitted, Fcc6) {
  const Truth truth("fcc6");
  BOXGEN_CHECK_EMITTED(fcc6, truth, 3);
  BOXGEN_CHECK_EMITTED(fcc6_shifted, truth, 3);
  BOXGEN_CHECK_EMITTED(fcc6_bernstein, truth, 3);
}
TEST(Emitted, Cart7) {
  const Truth truth("cart7");
  BOXGEN_CHECK_EMITTED(cart7, truth, 3);
  BOXGEN_CHECK_EMITTED(cart7_shifted, truth, 3);
}
TEST(Emitted, Tricubic) {
  const Truth truth("tricubic");
  BOXGEN_CHECK_EMITTED(tricubic, truth, 3);
  BOXGEN_CHECK_EMITTED(tricubic_horner, truth, 3);
}
TEST(Emitted, ZwartPowell) {
  const Truth truth("zp");
  BOXGEN_CHECK_EMITTED(zp, truth, 2);
  BOXGEN_CHECK_EMITTED(zp_monomial, truth, 2);
  BOXGEN_CHECK_EMITTED(zp_shifted, truth, 2);
  BOXGEN_CHECK_EMITTED(zp_bernstein, truth, 2);
}
TEST(Emitted, Biquadratic) {
  const Truth truth("1,0; 0,1; 1,0; 0,1; 1,0; 0,1");
  BOXGEN_CHECK_EMITTED(biquadratic, truth, 2);
}
// Scaled pairs: derived on the reduced pair, located in cubes of side k (Traits::kScale).
TEST(Emitted, M7Doubled) {
  const Truth truth("2,2,2; 2,-2,-2; -2,2,-2; -2,-2,2; 4,0,0; 0,4,0; 0,0,4",
                    "-2,2,2; 2,-2,2; 2,2,-2");
  BOXGEN_CHECK_EMITTED(m7_doubled, truth, 3);
}
TEST(Emitted, ZwartPowellTripled) {
  const Truth truth("3,0; 0,3; 3,3; -3,3", "3,0; 0,3");
  BOXGEN_CHECK_EMITTED(zp_tripled, truth, 2);
}

}  // namespace
}  // namespace boxgen::generator

namespace {

// The headers above really are the strategies named (so every form is what was checked), and
// `auto` chose the separable form for the tensor products and the shifted Horner form for M7 and
// M8 (a few operations fewer than Horner about the corner; Bernstein-Bezier costs far more).
TEST(Emitted, HeadersNameTheirStrategy) {
  EXPECT_STREQ(boxgen::generated::m7::kStrategy, "shifted");
  EXPECT_STREQ(boxgen::generated::m8::kStrategy, "shifted");
  EXPECT_STREQ(boxgen::generated::m7_horner::kStrategy, "horner");
  EXPECT_STREQ(boxgen::generated::m8_horner::kStrategy, "horner");
  EXPECT_STREQ(boxgen::generated::m12_shifted::kStrategy, "shifted");
  EXPECT_STREQ(boxgen::generated::zp_shifted::kStrategy, "shifted");
  EXPECT_STREQ(boxgen::generated::fcc6_shifted::kStrategy, "shifted");
  EXPECT_STREQ(boxgen::generated::cart7_shifted::kStrategy, "shifted");
  EXPECT_STREQ(boxgen::generated::m7_bernstein::kStrategy, "bernstein");
  EXPECT_STREQ(boxgen::generated::m8_bernstein::kStrategy, "bernstein");
  EXPECT_STREQ(boxgen::generated::fcc6_bernstein::kStrategy, "bernstein");
  EXPECT_STREQ(boxgen::generated::zp_bernstein::kStrategy, "bernstein");
  EXPECT_STREQ(boxgen::generated::m12::kStrategy, "separable");
  EXPECT_STREQ(boxgen::generated::tricubic::kStrategy, "separable");
  EXPECT_STREQ(boxgen::generated::m12_horner::kStrategy, "horner");
  EXPECT_STREQ(boxgen::generated::tricubic_horner::kStrategy, "horner");
  EXPECT_STREQ(boxgen::generated::m7_monomial::kStrategy, "monomial");
  EXPECT_STREQ(boxgen::generated::zp::kStrategy, "horner");
  EXPECT_STREQ(boxgen::generated::zp_monomial::kStrategy, "monomial");
  EXPECT_STREQ(boxgen::generated::biquadratic::kStrategy, "separable");
  EXPECT_STREQ(boxgen::generated::cart7::kStrategy, "monomial");
}

// The recorded counts are the cost model `auto` chose by: the separable M12 is far cheaper than
// its Horner form, and every path costs at least the one before it.
TEST(Emitted, HeadersRecordTheirOperationCounts) {
  EXPECT_LT(boxgen::generated::m12::kGradientOperations,
            boxgen::generated::m12_horner::kGradientOperations / 4);
  EXPECT_LT(boxgen::generated::tricubic::kGradientOperations,
            boxgen::generated::tricubic_horner::kGradientOperations);
  // auto chose by these counts: its M7 and M8 cost no more than either other form of them.
  EXPECT_LE(boxgen::generated::m7::kGradientOperations,
            boxgen::generated::m7_horner::kGradientOperations);
  EXPECT_LE(boxgen::generated::m7::kGradientOperations,
            boxgen::generated::m7_bernstein::kGradientOperations);
  EXPECT_LE(boxgen::generated::m8::kGradientOperations,
            boxgen::generated::m8_horner::kGradientOperations);
  EXPECT_LE(boxgen::generated::m8::kGradientOperations,
            boxgen::generated::m8_bernstein::kGradientOperations);
  EXPECT_LT(boxgen::generated::m7::kValueOperations, boxgen::generated::m7::kGradientOperations);
  EXPECT_LT(boxgen::generated::m7::kGradientOperations, boxgen::generated::m7::kHessianOperations);
}

}  // namespace
