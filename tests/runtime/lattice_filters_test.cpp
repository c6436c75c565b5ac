// Every filter of generated/registry.hpp through the runtime on its own lattice
// (runtime/spline_filter.h, reconstruction.h, resample.h). Each test loops over the registry, so a
// filter added there is covered without a change here.
//
// Oracle: quasi-interpolation with Q^I (and Q^II) of a filter of approximation order k reproduces
// every polynomial of degree < k, with its derivatives. The polynomial (every monomial of degree
// < k, with coefficients written out below) and its gradient are evaluated here directly; the
// prefilter weights, the evaluator and k come from the generator.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "runtime/prefilter.h"
#include "runtime/reconstruction.h"
#include "runtime/resample.h"
#include "runtime/sampling.h"
#include "runtime/test_functions.h"
#include "tests/support/bcc_volumes.h"

namespace boxgen::runtime {
namespace {

// sum over a + b + c < order of w(a, b, c) x^a y^b z^c, w = ((a + 2b + 3c) mod 5) - 1.5: every
// monomial of degree < order has a non-zero coefficient.
struct Polynomial {
  int order;
  static double weight(int a, int b, int c) { return ((a + 2 * b + 3 * c) % 5) - 1.5; }
  double operator()(const Vec3& p) const {
    double s = 0;
    for (int a = 0; a < order; ++a)
      for (int b = 0; a + b < order; ++b)
        for (int c = 0; a + b + c < order; ++c)
          s += weight(a, b, c) * std::pow(p[0], a) * std::pow(p[1], b) * std::pow(p[2], c);
    return s;
  }
  Vec3 gradient(const Vec3& p) const {
    Vec3 g{};
    for (int a = 0; a < order; ++a)
      for (int b = 0; a + b < order; ++b)
        for (int c = 0; a + b + c < order; ++c) {
          const double w = weight(a, b, c);
          if (a > 0) g[0] += w * a * std::pow(p[0], a - 1) * std::pow(p[1], b) * std::pow(p[2], c);
          if (b > 0) g[1] += w * b * std::pow(p[0], a) * std::pow(p[1], b - 1) * std::pow(p[2], c);
          if (c > 0) g[2] += w * c * std::pow(p[0], a) * std::pow(p[1], b) * std::pow(p[2], c - 1);
        }
    return g;
  }
};

std::vector<SplineFilter> registry() {
  std::vector<SplineFilter> out;
  for (int i = 0; i < SplineFilter::count(); ++i) out.push_back(SplineFilter::at(i));
  return out;
}

TEST(SplineFilters, HoldTheIssuesFiltersOnTheirLattices) {
  std::set<std::string> seen;
  for (const SplineFilter& f : registry()) {
    seen.insert(f.name());
    EXPECT_EQ(SplineFilter::parse(f.name()).registry_index(), f.registry_index());
  }
  const std::pair<const char*, const char*> expected[] = {{"m7", "bcc"},
                                                          {"m8", "bcc"},
                                                          {"m12", "bcc"},
                                                          {"fcc6", "fcc"},
                                                          {"tricubic", "cartesian"},
                                                          {"cart7", "cartesian"}};
  for (const auto& [name, lattice] : expected) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(seen.count(name));
    EXPECT_EQ(SplineFilter::parse(name).lattice().name(), lattice);
  }
  try {
    (void)SplineFilter::parse("m9");
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "unknown filter 'm9': expected " + SplineFilter::names());
    EXPECT_NE(SplineFilter::names().find("fcc6"), std::string::npos);
  }
}

// The issue's exactness claim for every registry filter: samples of a polynomial of degree < k on
// the filter's lattice (the margin required_margin gives), prefiltered with q1 and with q2, give
// back the polynomial to 1e-11 and its gradient to 1e-9, at random points and at the cube's
// corners and faces (which required_margin must cover).
TEST(SplineFilters, PrefilteredReconstructionReproducesPolynomialsBelowTheOrder) {
  for (const SplineFilter& f : registry()) {
    SCOPED_TRACE(f.name());
    const int order = f.approximation_order();
    ASSERT_GE(order, 3) << "every registry filter reproduces at least quadratics";
    const Polynomial poly{order};
    const auto fn = [&](const Vec3& p) { return poly(p); };
    for (const PrefilterChoice q : {PrefilterChoice::Q1, PrefilterChoice::Q2}) {
      LatticeVolume<double> v =
          sample_lattice<double>(fn, cube_lattice_grid(f.lattice(), 6, f.required_margin(q)));
      v = prefilter(v, f.prefilter(q));
      const Reconstructor<double> r(v, f);
      std::vector<Vec3> points;
      std::mt19937_64 rng(5);
      std::uniform_real_distribution<double> u(-1, 1);
      for (int i = 0; i < 150; ++i) points.push_back({u(rng), u(rng), u(rng)});
      for (double x : {-1.0, 1.0})
        for (double y : {-1.0, 1.0})
          for (double z : {-1.0, 0.0, 1.0}) points.push_back({x, y, z});
      std::vector<double> values(points.size());
      std::vector<Vec3> gradients(points.size());
      r.evaluate(points, values, gradients);
      for (std::size_t i = 0; i < points.size(); ++i) {
        const Vec3& p = points[i];
        EXPECT_NEAR(values[i], poly(p), 1e-11) << p[0] << " " << p[1] << " " << p[2];
        const Vec3 g = poly.gradient(p);
        for (int a = 0; a < 3; ++a) EXPECT_NEAR(gradients[i][a], g[a], 1e-9) << i << " " << a;
      }
    }
  }
}

TEST(SplineFilters, AVolumeOfAnotherLatticeIsOneLine) {
  const CosetLattice lattices[] = {CosetLattice::bcc(), CosetLattice::fcc(),
                                   CosetLattice::cartesian(),
                                   CosetLattice::parse("1,0,0; 0,1,0; 0,0,2")};
  for (const SplineFilter& f : registry())
    for (const CosetLattice& l : lattices) {
      if (same_points(f.lattice(), l)) continue;
      SCOPED_TRACE(std::string(f.name()) + " on " + l.name());
      const LatticeVolume<float> v(l, {8, 8, 8}, 0.25, {0, 0, 0});
      try {
        const Reconstructor<float> r(v, f);
        ADD_FAILURE() << "no error";
      } catch (const std::invalid_argument& e) {
        EXPECT_EQ(std::string(e.what()),
                  std::string("filter ") + f.name() + " is for the " + f.lattice().name() +
                      " lattice, but the volume is on the " + l.name() + " lattice");
      }
      EXPECT_THROW((void)default_box(v, f), std::invalid_argument);
    }
}

// On BCC two fetch implementations, one evaluator: BCC's parity tables (the offsets (0,0,0)
// (1,1,1)) and the general lattice tables (the same samples stored with the cosets swapped).
TEST(SplineFilters, OnBccTheParityPathAgreesWithTheLatticePath) {
  const CosetLattice bcc = CosetLattice::bcc();
  const LatticeVolume<double> parity =
      sample_lattice<double>(marschner_lobb, cube_lattice_grid(bcc, 9, 3));
  const LatticeVolume<double> swapped = test::swapped_cosets(parity);
  for (const SplineFilter& f : registry()) {
    if (!(f.lattice() == bcc)) continue;
    SCOPED_TRACE(f.name());
    const Reconstructor<double> general(swapped, f);
    const Reconstructor<double> special(parity, f);
    std::mt19937_64 rng(2);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<Vec3> points(100);
    for (Vec3& p : points) p = {u(rng), u(rng), u(rng)};
    for (const Vec3& p : points) {
      Vec3 g{}, g_bcc{};
      Hessian h{}, h_bcc{};
      EXPECT_NEAR(general.value(p, &g, &h), special.value_gradient_hessian(p, g_bcc, h_bcc), 1e-14);
      for (int a = 0; a < 3; ++a) EXPECT_NEAR(g[a], g_bcc[a], 1e-11);
      for (int a = 0; a < 6; ++a) EXPECT_NEAR(h[a], h_bcc[a], 1e-8);
    }
    std::vector<double> batch(points.size()), batch_bcc(points.size());
    general.evaluate(points, batch);
    special.evaluate(points, batch_bcc);
    for (std::size_t i = 0; i < points.size(); ++i) EXPECT_EQ(batch[i], batch_bcc[i]);
  }
}

// Resampling: the default box evaluates everywhere (and one grid step more does not), and each
// grid value is the spline's value at the grid point.
TEST(SplineFilters, ResampleGivesTheSplineOnTheDefaultBox) {
  for (const SplineFilter& f : registry()) {
    SCOPED_TRACE(f.name());
    const LatticeVolume<double> v = sample_lattice<double>(
        marschner_lobb,
        cube_lattice_grid(f.lattice(), 5, f.required_margin(PrefilterChoice::None)));
    const Box box = default_box(v, f);
    const CartesianGrid grid = grid_over(box, {4, 5, 3});
    const CartesianVolume<double> out = resample(v, f, grid);
    const Reconstructor<double> r(v, f);
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 4; ++i)
          EXPECT_EQ(out.values[out.index(i, j, k)], r.value(out.position(i, j, k)));
    const Box region = evaluable_region(v, f);
    for (int a = 0; a < 3; ++a) {
      EXPECT_LE(region.min[a], box.min[a]);
      EXPECT_LT(box.max[a], region.max[a]);
    }
    CartesianGrid beyond = grid;
    beyond.origin[0] -= grid.spacing[0];
    EXPECT_THROW((void)resample(v, f, beyond), std::out_of_range);
    const LatticeVolume<double> tiny(f.lattice(), {1, 1, 1}, 1.0, {0, 0, 0});
    EXPECT_THROW((void)default_box(tiny, f), std::invalid_argument);
  }
}

}  // namespace
}  // namespace boxgen::runtime
