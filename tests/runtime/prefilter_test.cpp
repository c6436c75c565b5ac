// Discrete convolution V * q with the shrinking border policy. The filters here are made up for
// the tests (the real Q^I, Q^II come from the generator as data).
#include "runtime/prefilter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

namespace boxgen::runtime {
namespace {

// A non-linear function of the lattice point, so that every misplaced sample shows.
double lattice_function(std::int64_t x, std::int64_t y, std::int64_t z) {
  return static_cast<double>(x * x + 3 * y + 7 * z * x);
}

template <class T>
LatticeVolume<T> lattice_volume(Sizes sizes, double h = 1, Vec3 origin = {0, 0, 0}) {
  LatticeVolume<T> v(CosetLattice::bcc(), sizes, h, origin);
  for (int k = 0; k < sizes[2]; ++k)
    for (int j = 0; j < sizes[1]; ++j)
      for (int i = 0; i < sizes[0]; ++i)
        for (int c = 0; c < 2; ++c)
          v(c, i, j, k) = static_cast<T>(lattice_function(2 * i + c, 2 * j + c, 2 * k + c));
  return v;
}

// q = 2 at 0, 1/2 at (1,1,1), -1/4 at (-1,-1,1), 1 at (2,0,0).
const PrefilterTaps kFilter = {
    {{0, 0, 0}, 2.0}, {{1, 1, 1}, 0.5}, {{-1, -1, 1}, -0.25}, {{2, 0, 0}, 1.0}};

TEST(BccPrefilter, ShrinkFollowsTheOffsets) {
  // Axis x: offsets 0, 1, -1, 2: lower ceil(2/2) = 1, upper ceil(1/2) = 1. Axis y: 0, 1, -1, 0:
  // 1 and 1. Axis z: 0, 1, 1, 0: lower 1, upper 0.
  const PrefilterShrink s = prefilter_shrink(kFilter, CosetLattice::bcc());
  EXPECT_EQ(s.lower, (Sizes{1, 1, 1}));
  EXPECT_EQ(s.upper, (Sizes{1, 1, 0}));
  EXPECT_EQ(prefilter_margin(kFilter, CosetLattice::bcc()), 1);
  EXPECT_EQ(prefilter_margin({{{0, 0, 0}, 1.0}}, CosetLattice::bcc()), 0);
  // Taps on the shells S1 and S2 (max-norm 2), the support of Q^I and Q^II: one cell.
  PrefilterTaps shells{{{0, 0, 0}, 1.0}};
  for (int sx : {-1, 1})
    for (int sy : {-1, 1})
      for (int sz : {-1, 1}) shells.push_back({{sx, sy, sz}, 0.1});
  for (int a = 0; a < 3; ++a)
    for (int s2 : {-2, 2}) {
      std::array<int, 3> o{0, 0, 0};
      o[a] = s2;
      shells.push_back({o, 0.1});
    }
  EXPECT_EQ(prefilter_margin(shells, CosetLattice::bcc()), 1);
  EXPECT_EQ(prefilter_margin({{{3, 3, -3}, 1.0}}, CosetLattice::bcc()), 2);
}

TEST(BccPrefilter, HandComputedSamples) {
  const auto v = lattice_volume<double>({4, 4, 4}, 0.5, {1, 2, 3});
  const auto out = prefilter(v, kFilter);
  EXPECT_EQ(out.sizes(), (Sizes{2, 2, 3}));
  EXPECT_EQ(out.spacing(), 0.5);
  EXPECT_EQ(out.origin(), (Vec3{2, 3, 4}));  // o + 2 h (1, 1, 1)
  // Output (0,0,0,0) is input lattice point (2,2,2), V = x^2 + 3y + 7zx:
  //   2 V(2,2,2) + 1/2 V(1,1,1) - 1/4 V(3,3,1) + V(0,2,2) = 2*38 + 11/2 - 39/4 + 6 = 77.75.
  EXPECT_EQ(out.at(0, 0, 0, 0), 77.75);
  // Output (1,1,0,2) is input lattice point (5,3,7):
  //   2 V(5,3,7) + 1/2 V(4,2,6) - 1/4 V(6,4,6) + V(3,3,7) = 2*279 + 190/2 - 300/4 + 165 = 743.
  EXPECT_EQ(out.at(1, 1, 0, 2), 743.0);
  // World positions are kept: output sample (c, i, j, k) is input sample (c, i+1, j+1, k+1).
  for (int c = 0; c < 2; ++c)
    EXPECT_EQ(out.sample_position(c, 1, 1, 2), v.sample_position(c, 2, 2, 3));
}

TEST(BccPrefilter, IdentityFilterReturnsTheVolume) {
  const auto v = lattice_volume<float>({3, 2, 4}, 0.1, {-1, 0, 1});
  const auto out = prefilter(v, {{{0, 0, 0}, 1.0}});
  EXPECT_EQ(out.sizes(), v.sizes());
  EXPECT_EQ(out.origin(), v.origin());
  EXPECT_EQ(out.spacing(), v.spacing());
  for (std::size_t s = 0; s < v.sample_count(); ++s) EXPECT_EQ(out.samples()[s], v.samples()[s]);
}

// Every output sample against the definition, summed through the checked lattice access: a
// border policy that kept a sample whose neighbourhood leaves the volume would throw here.
TEST(BccPrefilter, AgreesWithTheDefinitionForRandomFilters) {
  std::mt19937 random(7);
  std::uniform_int_distribution<int> offset(-2, 2), parity(0, 1);
  std::uniform_real_distribution<double> weight(-1, 1);
  const auto v = lattice_volume<double>({8, 9, 10});  // taps reach 5 units: 3 cells per side
  for (int trial = 0; trial < 20; ++trial) {
    PrefilterTaps q;
    const int taps = 1 + trial % 6;
    for (int t = 0; t < taps; ++t) {
      const int p = parity(random);
      q.push_back({{2 * offset(random) + p, 2 * offset(random) + p, 2 * offset(random) + p},
                   weight(random)});
    }
    const auto out = prefilter(v, q);
    const PrefilterShrink s = prefilter_shrink(q, CosetLattice::bcc());
    for (int a = 0; a < 3; ++a) EXPECT_EQ(out.sizes()[a], v.sizes()[a] - s.lower[a] - s.upper[a]);
    for (int k = 0; k < out.sizes()[2]; ++k)
      for (int j = 0; j < out.sizes()[1]; ++j)
        for (int i = 0; i < out.sizes()[0]; ++i)
          for (int c = 0; c < 2; ++c) {
            const LatticePoint x{2 * (i + s.lower[0]) + c, 2 * (j + s.lower[1]) + c,
                                 2 * (k + s.lower[2]) + c};
            double expected = 0;
            for (const auto& [o, w] : q)
              expected += w * v.value(x[0] - o[0], x[1] - o[1], x[2] - o[2]);
            ASSERT_NEAR(out.at(c, i, j, k), expected, 1e-12 * (1 + std::fabs(expected)))
                << "trial " << trial;
          }
  }
}

// The shrink is tight: one more coset cell at either end would need a sample that is not there.
TEST(BccPrefilter, ShrinkIsNoLargerThanNeeded) {
  const LatticeVolume<double> v(CosetLattice::bcc(), {6, 6, 6}, 1, {0, 0, 0});
  const PrefilterTaps q = {{{0, 0, 0}, 1.0}, {{1, 1, 1}, 1.0}, {{-2, 0, 0}, 1.0}, {{0, 2, 0}, 1.0}};
  const PrefilterShrink s = prefilter_shrink(q, CosetLattice::bcc());
  for (int a = 0; a < 3; ++a) {
    auto neighbourhood_inside = [&](std::int64_t x_a) {
      for (int c = 0; c < 2; ++c)
        for (const auto& [o, w] : q) {
          LatticePoint x{2, 2, 2};  // inside on the other axes
          for (int b = 0; b < 3; ++b) x[b] += c;
          x[a] = x_a + c;
          if (!v.contains(x[0] - o[0], x[1] - o[1], x[2] - o[2])) return false;
        }
      return true;
    };
    if (s.lower[a] > 0) {
      EXPECT_FALSE(neighbourhood_inside(2 * std::int64_t{s.lower[a] - 1})) << "axis " << a;
    }
    const int last = v.sizes()[a] - s.upper[a];  // first coset index past the output
    if (s.upper[a] > 0) {
      EXPECT_FALSE(neighbourhood_inside(2 * std::int64_t{last})) << "axis " << a;
    }
    EXPECT_TRUE(neighbourhood_inside(2 * std::int64_t{s.lower[a]})) << "axis " << a;
    EXPECT_TRUE(neighbourhood_inside(2 * std::int64_t{last - 1})) << "axis " << a;
  }
}

TEST(BccPrefilter, FloatAgreesWithDouble) {
  const auto d = lattice_volume<double>({5, 5, 5});
  const auto f = lattice_volume<float>({5, 5, 5});
  const auto qd = prefilter(d, kFilter);
  const auto qf = prefilter(f, kFilter);
  ASSERT_EQ(qd.sample_count(), qf.sample_count());
  for (std::size_t s = 0; s < qd.sample_count(); ++s)
    EXPECT_NEAR(qf.samples()[s], qd.samples()[s], 1e-6 * (1 + std::fabs(qd.samples()[s])));
}

TEST(BccPrefilter, BadFiltersAndSmallVolumesAreErrors) {
  const auto v = lattice_volume<double>({3, 3, 3});
  const PrefilterTaps bad[] = {
      {},                                          // no taps
      {{{1, 0, 0}, 1.0}},                          // not a BCC lattice vector
      {{{0, 0, 0}, std::nan("")}},                 // weight not finite
      {{{0, 0, 0}, 1.0}, {{2, 2, 1 << 21}, 1.0}},  // absurd offset
  };
  for (const auto& q : bad) {
    try {
      (void)prefilter(v, q);
      ADD_FAILURE() << "no error";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  }
  // Taps reaching 4 lattice units each way cost 2 coset cells per side: 3 samples are too few.
  EXPECT_THROW((void)prefilter(v, {{{4, 4, 4}, 1.0}, {{-4, -4, -4}, 1.0}}), std::invalid_argument);
  const LatticeVolume<double> one(CosetLattice::bcc(), {1, 1, 1}, 1, {0, 0, 0});
  EXPECT_THROW((void)prefilter(one, {{{1, 1, 1}, 1.0}, {{-1, -1, -1}, 1.0}}),
               std::invalid_argument);
  EXPECT_NO_THROW((void)prefilter(one, {{{0, 0, 0}, 1.0}}));
}

}  // namespace
}  // namespace boxgen::runtime
