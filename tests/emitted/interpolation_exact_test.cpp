// Interpolation's view of a filter against the generator's exact one: the values M(k) at the
// lattice points that runtime/interpolation.h reads from the evaluator (in double) are the exact
// |det G| M_Xi(k + c) of the piecewise form, for every registry filter and for a SPEC filter on FCC
// emitted at build time (fcc7: the six FCC directions and (1,1,0) again); and interpolation with
// that SPEC filter passes through every sample.
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <string>

#include "emitted/fcc7.hpp"
#include "emitted/fcc7_prefilters.hpp"
#include "generator/piece_checks.h"
#include "generator/piecewise_form.h"
#include "generator/spec.h"
#include "runtime/emitted_filter.h"
#include "runtime/interpolation.h"
#include "runtime/reconstruction.h"
#include "runtime/resample.h"

namespace boxgen::generator {
namespace {

namespace rt = boxgen::runtime;

// Every lattice point k with |k_a| <= reach and its exact value M(k), zero ones included.
std::map<std::array<int, 3>, double> exact_values(const std::string& spec_text,
                                                  const std::string& lattice, int reach) {
  const BoxSplineSpec spec = parse_spec(spec_text, lattice);
  const PiecewiseForm form = derive_piecewise(spec, DerivationMethod::TruncatedPower);
  const RatVec centre = spline_centre(spec);
  const Rational det = Rational(spec.lattice.det_abs());
  const rt::CosetLattice runtime_lattice = rt::CosetLattice::parse(lattice);
  std::map<std::array<int, 3>, double> out;
  for (int z = -reach; z <= reach; ++z)
    for (int y = -reach; y <= reach; ++y)
      for (int x = -reach; x <= reach; ++x) {
        if (!runtime_lattice.contains(x, y, z)) continue;
        const RatVec u{Rational(x) + centre[0], Rational(y) + centre[1], Rational(z) + centre[2]};
        out[{x, y, z}] = to_double(det * form.value_at(u));
      }
  return out;
}

void expect_exact(const rt::SplineFilter& f, const std::string& spec, const std::string& lattice) {
  const rt::PrefilterTaps values = rt::lattice_values(f);
  int reach = 0;
  for (const auto& [k, w] : values)
    for (int a : k) reach = std::max(reach, std::abs(a) + 1);  // one layer of zeros around
  const auto exact = exact_values(spec, lattice, reach);
  std::size_t nonzero = 0;
  for (const auto& [k, v] : exact) nonzero += v != 0;
  EXPECT_EQ(values.size(), nonzero) << f.name();
  for (const auto& [k, w] : values) {
    const auto it = exact.find(k);
    ASSERT_NE(it, exact.end()) << f.name();
    EXPECT_NEAR(w, it->second, 1e-15) << f.name() << " at " << k[0] << " " << k[1] << " " << k[2];
  }
}

TEST(InterpolationExact, LatticeValuesOfEveryRegistryFilterAreExact) {
  for (int i = 0; i < rt::SplineFilter::count(); ++i) {
    const rt::SplineFilter f = rt::SplineFilter::at(i);
    expect_exact(f, f.name(), f.lattice().name());
  }
}

rt::SplineFilter fcc7() {
  return rt::emitted_filter<generated::fcc7::Traits>(generated::fcc7::q1, generated::fcc7::q2,
                                                     generated::fcc7::kApproximationOrder);
}

TEST(InterpolationExact, ASpecFilterOnFccIsExactAndInterpolates) {
  const rt::SplineFilter f = fcc7();
  expect_exact(f, "1,1,0; 1,-1,0; 1,0,1; 1,0,-1; 0,1,1; 0,1,-1; 1,1,0", "fcc");
  rt::LatticeVolume<double> v(rt::CosetLattice::fcc(), {7, 8, 6}, 0.5, {1, 2, 3});
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1, 1);
  for (double& s : v.samples()) s = u(rng);
  const rt::SymbolBounds b = rt::symbol_bounds(rt::lattice_values(f));
  ASSERT_GT(b.min, rt::kVanishing * b.max) << "fcc7's symbol vanishes: no exact interpolation";
  const rt::LatticeVolume<double> c = rt::interpolate(v, f);
  const rt::Reconstructor<double> spline(c, f);
  double worst = 0, largest = 0;
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 7; ++i)
        for (int q = 0; q < 4; ++q) {
          largest = std::max(largest, std::abs(v(q, i, j, k)));
          worst = std::max(worst,
                           std::abs(spline.value(v.sample_position(q, i, j, k)) - v(q, i, j, k)));
        }
  EXPECT_LE(worst, 1e-12 * largest);
}

}  // namespace
}  // namespace boxgen::generator
