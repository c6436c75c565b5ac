// The runtime with any emitted filter on its own lattice (runtime/emitted_filter.h):
// M7, M8, M12 on BCC (generated/), fcc6 on FCC and tricubic and cart7 on the Cartesian lattice
// (emitted at build time by tests/emitted/CMakeLists.txt, as a user's boxgen_emit() would).
//
// Oracle: quasi-interpolation with Q^I of a filter of approximation order k reproduces every
// polynomial of degree < k. The polynomials are written out here; the prefilter weights and the
// evaluator come from the generator. The Marschner-Lobb errors at (nearly) equal sample counts
// are measured and printed for the README's table; the test checks only what must hold.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "emitted/cart7.hpp"
#include "emitted/cart7_prefilters.hpp"
#include "emitted/fcc6.hpp"
#include "emitted/fcc6_prefilters.hpp"
#include "emitted/m7_doubled.hpp"
#include "emitted/m7_doubled_prefilters.hpp"
#include "emitted/tricubic.hpp"
#include "emitted/tricubic_prefilters.hpp"
#include "generated/m12.hpp"
#include "generated/m12_prefilters.hpp"
#include "generated/m7.hpp"
#include "generated/m7_prefilters.hpp"
#include "generated/m8.hpp"
#include "generated/m8_prefilters.hpp"
#include "runtime/emitted_filter.h"
#include "runtime/reconstruction.h"
#include "runtime/sampling.h"
#include "runtime/test_functions.h"
#include "tests/support/bcc_volumes.h"

namespace boxgen::runtime {
namespace {

namespace gen = boxgen::generated;

// x^3 - 2xyz + 3y^2 - z + 1 (degree 3) and 2x^2 - xy + 3z^2 - y + 0.5 (degree 2).
double cubic_poly(const Vec3& p) {
  return p[0] * p[0] * p[0] - 2 * p[0] * p[1] * p[2] + 3 * p[1] * p[1] - p[2] + 1;
}
double quadratic_poly(const Vec3& p) {
  return 2 * p[0] * p[0] - p[0] * p[1] + 3 * p[2] * p[2] - p[1] + 0.5;
}

// Coset cells of margin: the stencil reach (lattice units) over d, plus one for the prefilter.
template <class Tr>
int margin_for(const CosetLattice& lattice) {
  int reach = 0;
  for (int a = 0; a < 3; ++a)
    reach = std::max({reach, -Tr::kStencilReachLo[a] + static_cast<int>(std::ceil(Tr::kCentre[a])),
                      Tr::kStencilReachHi[a] + 1});
  return (reach + lattice.period() - 1) / lattice.period() + 2;
}

template <class Tr, class Tap, std::size_t N>
void expect_reproduction(const char* expected_lattice, const Tap (&q1)[N], int degree) {
  SCOPED_TRACE(Tr::kName);
  const CosetLattice lattice = filter_lattice<Tr>();
  EXPECT_EQ(lattice.name(), expected_lattice);
  const auto f = degree == 3 ? cubic_poly : quadratic_poly;
  LatticeVolume<double> v =
      sample_lattice<double>(f, cube_lattice_grid(lattice, 9, margin_for<Tr>(lattice)));
  v = prefilter(v, prefilter_from(q1));
  const Reconstructor<double> r(v, emitted_filter<Tr>());
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 300; ++i) {
    const Vec3 p{u(rng), u(rng), u(rng)};
    EXPECT_NEAR(r.value(p), f(p), 1e-11) << p[0] << " " << p[1] << " " << p[2];
  }
  // Grid points of the cube too, where cells meet.
  for (double x : {-1.0, -0.5, 0.0, 0.75, 1.0}) {
    const Vec3 p{x, -x, 0.5 * x};
    EXPECT_NEAR(r.value(p), f(p), 1e-11) << x;
  }
}

TEST(LatticeReconstruction, Q1ReproducesPolynomialsOfEveryFilterOnItsLattice) {
  // Approximation order 4 (the prefilter headers say so): cubics. fcc6 has order 3: quadratics.
  expect_reproduction<gen::m7::Traits>("bcc", gen::m7::q1, 3);
  expect_reproduction<gen::m8::Traits>("bcc", gen::m8::q1, 3);
  expect_reproduction<gen::m12::Traits>("bcc", gen::m12::q1, 3);
  expect_reproduction<gen::tricubic::Traits>("cartesian", gen::tricubic::q1, 3);
  expect_reproduction<gen::cart7::Traits>("cartesian", gen::cart7::q1, 3);
  expect_reproduction<gen::fcc6::Traits>("fcc", gen::fcc6::q1, 2);
  // A scaled pair (M7 doubled on 2 BCC): located in cubes of side 2 (Traits::kScale).
  expect_reproduction<gen::m7_doubled::Traits>("custom", gen::m7_doubled::q1, 3);
}

TEST(LatticeReconstruction, GradientsOfAReproducedPolynomialAreExact) {
  const CosetLattice lattice = filter_lattice<gen::fcc6::Traits>();
  LatticeVolume<double> v =
      sample_lattice<double>(quadratic_poly, cube_lattice_grid(lattice, 9, 6));
  v = prefilter(v, prefilter_from(gen::fcc6::q1));
  const Reconstructor<double> r(v, emitted_filter<gen::fcc6::Traits>());
  for (const Vec3& p : {Vec3{0.1, 0.2, -0.3}, Vec3{-0.7, 0.4, 0.9}}) {
    Vec3 g{};
    std::array<double, 6> hessian{};
    EXPECT_NEAR(r.value(p, &g, &hessian), quadratic_poly(p), 1e-11);
    EXPECT_NEAR(g[0], 4 * p[0] - p[1], 1e-9);
    EXPECT_NEAR(g[1], -p[0] - 1, 1e-9);
    EXPECT_NEAR(g[2], 6 * p[2], 1e-9);
    EXPECT_NEAR(hessian[0], 4, 1e-7);   // xx
    EXPECT_NEAR(hessian[1], -1, 1e-7);  // xy
    EXPECT_NEAR(hessian[5], 6, 1e-7);   // zz
  }
}

TEST(LatticeReconstruction, AFilterOnAVolumeOfAnotherLatticeIsOneError) {
  const LatticeVolume<double> fcc =
      sample_lattice<double>(cubic_poly, cube_lattice_grid(CosetLattice::fcc(), 5, 4));
  try {
    const Reconstructor<double> r(fcc, emitted_filter<gen::m7::Traits>());
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "filter m7 is for the bcc lattice, but the volume is on the fcc lattice");
  }
  const LatticeVolume<float> cart =
      sample_lattice<float>(cubic_poly, cube_lattice_grid(CosetLattice::cartesian(), 5, 4));
  EXPECT_THROW((Reconstructor<float>(cart, emitted_filter<gen::fcc6::Traits>())),
               std::invalid_argument);
  // The same points with the cosets in another order are the same lattice.
  const LatticeVolume<double> moved = sample_lattice<double>(
      cubic_poly,
      cube_lattice_grid(
          CosetLattice::fcc().with_offsets({{0, 1, 1}, {0, 0, 0}, {1, 1, 0}, {1, 0, 1}}), 5, 4));
  EXPECT_NO_THROW((Reconstructor<double>(moved, emitted_filter<gen::fcc6::Traits>())));
  // Points whose stencil leaves the volume, and non-finite points.
  const Reconstructor<double> r(moved, emitted_filter<gen::fcc6::Traits>());
  EXPECT_THROW((void)r.value({5, 0, 0}), std::out_of_range);
  EXPECT_THROW((void)r.value({1e300, 0, 0}), std::out_of_range);
  EXPECT_THROW((void)r.value({NAN, 0, 0}), std::invalid_argument);
}

// On BCC the generic lattice tables (the cosets stored the other way round) give what BCC's parity
// tables give, for every registry filter: two implementations of the fetch, one evaluator.
TEST(LatticeReconstruction, OnBccItAgreesWithTheBccParityPath) {
  const LatticeVolume<double> bcc = test::sample_bcc_cube<double>(marschner_lobb, 11, 3);
  const LatticeVolume<double> lattice = test::swapped_cosets(bcc);
  const Reconstructor<double> m7(lattice, emitted_filter<gen::m7::Traits>());
  const Reconstructor<double> m8(lattice, emitted_filter<gen::m8::Traits>());
  const Reconstructor<double> m12(lattice, emitted_filter<gen::m12::Traits>());
  const Reconstructor<double> r7(bcc, SplineFilter::parse("m7"));
  const Reconstructor<double> r8(bcc, SplineFilter::parse("m8"));
  const Reconstructor<double> r12(bcc, SplineFilter::parse("m12"));
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 500; ++i) {
    const Vec3 p{u(rng), u(rng), u(rng)};
    Vec3 g{}, g_bcc{};
    EXPECT_NEAR(m7.value(p, &g), r7.value(p, &g_bcc), 1e-14);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(g[a], g_bcc[a], 1e-12);
    EXPECT_NEAR(m8.value(p), r8.value(p), 1e-14);
    EXPECT_NEAR(m12.value(p), r12.value(p), 1e-14);
  }
}

// The stencil policy of a volume: BCC's parity tables only on BCC volumes with the offsets
// (0,0,0) (1,1,1); 64-bit offsets only where 32-bit ones cannot reach every sample (a z slice of
// 50000^2 samples per coset: over 2^31 whatever the reach) and the filter keeps that policy; a
// compiled filter does not, and such a volume takes the general lattice tables.
TEST(LatticeReconstruction, TheStencilPolicyOfAVolume) {
  using M7 = gen::m7::Traits;
  const CosetLattice bcc = CosetLattice::bcc();
  const Sizes small{1000, 1000, 1000}, large{50000, 50000, 1};
  EXPECT_EQ((stencil_policy<M7>(bcc, small)), StencilPolicy::kBcc32);
  EXPECT_EQ((stencil_policy<M7>(bcc, large)), StencilPolicy::kBcc64);
  EXPECT_EQ((stencil_policy<M7, false>(bcc, small)), StencilPolicy::kBcc32);
  EXPECT_EQ((stencil_policy<M7, false>(bcc, large)), StencilPolicy::kLattice);
  EXPECT_EQ((stencil_policy<M7>(bcc.with_offsets({{1, 1, 1}, {0, 0, 0}}), small)),
            StencilPolicy::kLattice);
  EXPECT_EQ((stencil_policy<gen::fcc6::Traits>(CosetLattice::fcc(), small)),
            StencilPolicy::kLattice);
}

// What such a large volume then gets: the general lattice tables on BCC volumes with the offsets
// (0,0,0) (1,1,1), here on a small one, give what the parity tables give; and a filter without
// the 64-bit policy takes the parity tables wherever 32-bit offsets fit.
TEST(LatticeReconstruction, OnBccTheLatticeTablesAgreeWithTheParityTables) {
  using M7 = gen::m7::Traits;
  const LatticeVolume<double> bcc = test::sample_bcc_cube<double>(marschner_lobb, 11, 3);
  const EmittedSplinePath<M7, LatticeStencils<M7, double>> general(LatticeStencils<M7, double>(bcc),
                                                                   -1);
  const auto narrow = emitted_path<M7, double, false>(bcc, -1, nullptr);
  const Reconstructor<double> parity(bcc, SplineFilter::parse("m7"));
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 500; ++i) {
    const Vec3 p{u(rng), u(rng), u(rng)};
    Vec3 g{}, g_parity{};
    const double expected = parity.value(p, &g_parity);
    EXPECT_NEAR(general.at(p, &g, nullptr), expected, 1e-14);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(g[a], g_parity[a], 1e-12);
    EXPECT_DOUBLE_EQ(narrow->at(p, nullptr, nullptr), parity.value(p));
  }
}

// RMS error of Marschner-Lobb over 100000 random points of [-1,1]^3 (seed 1) at density n.
template <class Tr, class Tap, std::size_t N>
double ml_rms(int n, const Tap (*q)[N]) {
  const CosetLattice lattice = filter_lattice<Tr>();
  LatticeVolume<double> v = sample_lattice<double>(
      marschner_lobb, cube_lattice_grid(lattice, n, margin_for<Tr>(lattice)));
  if (q) v = prefilter(v, prefilter_from(*q));
  const Reconstructor<double> r(v, emitted_filter<Tr>());
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  double sum2 = 0;
  constexpr int kPoints = 100000;
  for (int i = 0; i < kPoints; ++i) {
    const Vec3 p{u(rng), u(rng), u(rng)};
    const double e = r.value(p) - marschner_lobb(p);
    sum2 += e * e;
  }
  return std::sqrt(sum2 / kPoints);
}

// Samples per coset and axis for about the sample count of n^3 x 2 BCC samples: K m^3 = 2 n^3.
int equal_count_density(int n, int cosets) {
  return static_cast<int>(std::lround(n * std::cbrt(2.0 / cosets)));
}

TEST(LatticeReconstruction, MarschnerLobbAtEqualSampleCounts) {
  for (int n : {17, 33}) {
    const int nf = equal_count_density(n, 4), nc = equal_count_density(n, 1);
    const double m7_none = ml_rms<gen::m7::Traits, gen::m7::PrefilterTap, 1>(n, nullptr);
    const double m7_q1 = ml_rms<gen::m7::Traits>(n, &gen::m7::q1);
    const double fcc6_none = ml_rms<gen::fcc6::Traits, gen::fcc6::PrefilterTap, 1>(nf, nullptr);
    const double fcc6_q1 = ml_rms<gen::fcc6::Traits>(nf, &gen::fcc6::q1);
    const double tricubic_none =
        ml_rms<gen::tricubic::Traits, gen::tricubic::PrefilterTap, 1>(nc, nullptr);
    const double tricubic_q1 = ml_rms<gen::tricubic::Traits>(nc, &gen::tricubic::q1);
    std::printf(
        "ML rms at about %d samples: m7/bcc N=%d (%d) none %.4e q1 %.4e | fcc6/fcc N=%d (%d) none "
        "%.4e q1 %.4e | "
        "tricubic/cartesian N=%d (%d) none %.4e q1 %.4e\n",
        2 * n * n * n, n, 2 * n * n * n, m7_none, m7_q1, nf, 4 * nf * nf * nf, fcc6_none, fcc6_q1,
        nc, nc * nc * nc, tricubic_none, tricubic_q1);
    // What must hold: every reconstruction is finite and far better than the function's range
    // (0..1); at N = 33 (no longer badly under-sampled) Q^I helps each filter.
    for (double e : {m7_none, m7_q1, fcc6_none, fcc6_q1, tricubic_none, tricubic_q1}) {
      EXPECT_TRUE(std::isfinite(e));
      EXPECT_LT(e, 0.2);
    }
    if (n == 33) {
      EXPECT_LT(m7_q1, m7_none);
      EXPECT_LT(fcc6_q1, fcc6_none);
      EXPECT_LT(tricubic_q1, tricubic_none);
    }
  }
}

}  // namespace
}  // namespace boxgen::runtime
