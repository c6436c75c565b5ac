// Sampling on [-1,1]^3 (docs/design.md §13) and the margins that stencils need.
#include "runtime/sampling.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <vector>

#include "runtime/lattice_grid_choice.h"
#include "runtime/test_functions.h"
#include "tests/support/bcc_volumes.h"

namespace boxgen::runtime {
namespace {

TEST(BccSampling, CubeGridGeometry) {
  const LatticeGrid g = cube_lattice_grid(CosetLattice::bcc(), 33, 0);
  EXPECT_EQ(g.sizes, (Sizes{33, 33, 33}));
  EXPECT_EQ(g.h, 1.0 / 32);
  EXPECT_EQ(g.origin, (Vec3{-1, -1, -1}));
  const LatticeGrid m =
      cube_lattice_grid(CosetLattice::bcc(), 5, 2);  // h = 1/4, origin -1 - 2 h m = -2
  EXPECT_EQ(m.sizes, (Sizes{9, 9, 9}));
  EXPECT_EQ(m.h, 0.25);
  EXPECT_EQ(m.origin, (Vec3{-2, -2, -2}));
}

TEST(BccSampling, EvenPointsSpanTheCubeAndOddPointsAreCubeCentres) {
  const int n = 5;  // h = 1/4
  const auto x = test::sample_bcc_cube<double>([](const Vec3& p) { return p[0]; }, n, 0);
  const auto y = test::sample_bcc_cube<double>([](const Vec3& p) { return p[1]; }, n, 0);
  const auto z = test::sample_bcc_cube<double>([](const Vec3& p) { return p[2]; }, n, 0);
  EXPECT_EQ(x.at(0, 0, 0, 0), -1.0);
  EXPECT_EQ(x.at(0, n - 1, 0, 0), 1.0);
  EXPECT_EQ(z.at(0, 0, 0, n - 1), 1.0);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        // Primary points -1 + 2 h i.
        EXPECT_EQ(x.at(0, i, j, k), -1 + 0.5 * i);
        EXPECT_EQ(y.at(0, i, j, k), -1 + 0.5 * j);
        EXPECT_EQ(z.at(0, i, j, k), -1 + 0.5 * k);
        // The odd sample (1, i, j, k) is the centre of the cube between even samples i and i+1.
        if (i + 1 < n && j + 1 < n && k + 1 < n) {
          EXPECT_EQ(x.at(1, i, j, k), (x.at(0, i, j, k) + x.at(0, i + 1, j, k)) / 2);
          EXPECT_EQ(y.at(1, i, j, k), (y.at(0, i, j, k) + y.at(0, i, j + 1, k)) / 2);
          EXPECT_EQ(z.at(1, i, j, k), (z.at(0, i, j, k) + z.at(0, i, j, k + 1)) / 2);
        }
      }
}

TEST(BccSampling, MarginKeepsTheCubeAtTheSameWorldPositions) {
  const int n = 9, m = 3;  // h = 1/8
  const auto v = test::sample_bcc_cube<double>(marschner_lobb, n, m);
  EXPECT_EQ(v.sizes(), (Sizes{n + 2 * m, n + 2 * m, n + 2 * m}));
  // Lattice (2m, 2m, 2m) is the corner (-1,-1,-1), lattice 2m + 2N - 2 the corner (1,1,1).
  EXPECT_EQ(v.to_world({2.0 * m, 2.0 * m, 2.0 * m}), (Vec3{-1, -1, -1}));
  EXPECT_EQ(v.to_world({2.0 * m + 2 * n - 2, 2.0 * m + 2 * n - 2, 2.0 * m + 2 * n - 2}),
            (Vec3{1, 1, 1}));
  const auto plain = test::sample_bcc_cube<double>(marschner_lobb, n, 0);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (int c = 0; c < 2; ++c) EXPECT_EQ(v.at(c, i + m, j + m, k + m), plain.at(c, i, j, k));
}

TEST(BccSampling, FloatSamplesAreTheRoundedDoubleSamples) {
  const auto d = test::sample_bcc_cube<double>(gaussian, 6, 1);
  const auto f = test::sample_bcc_cube<float>(gaussian, 6, 1);
  ASSERT_EQ(d.sample_count(), f.sample_count());
  for (std::size_t s = 0; s < d.sample_count(); ++s)
    EXPECT_EQ(f.samples()[s], static_cast<float>(d.samples()[s]));
  EXPECT_EQ(f.spacing(), d.spacing());
  EXPECT_EQ(f.origin(), d.origin());
}

TEST(BccSampling, SampleBccPlacesEverySampleAtItsWorldPoint) {
  const LatticeGrid grid{CosetLattice::bcc(), {2, 3, 4}, 0.3, {0.5, -1, 2}};
  const auto v =
      sample_lattice<double>([](const Vec3& p) { return p[0] + 10 * p[1] + 100 * p[2]; }, grid);
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 2; ++i)
        for (int c = 0; c < 2; ++c) {
          const Vec3 p{0.5 + 0.3 * (2 * i + c), -1 + 0.3 * (2 * j + c), 2 + 0.3 * (2 * k + c)};
          EXPECT_NEAR(v.at(c, i, j, k), p[0] + 10 * p[1] + 100 * p[2], 1e-12);
        }
}

TEST(BccSampling, BadArgumentsAreRejected) {
  EXPECT_THROW(cube_lattice_grid(CosetLattice::bcc(), 1, 0), std::invalid_argument);
  EXPECT_THROW(cube_lattice_grid(CosetLattice::bcc(), -3, 0), std::invalid_argument);
  EXPECT_THROW(cube_lattice_grid(CosetLattice::bcc(), 5, -1), std::invalid_argument);
  EXPECT_THROW(cube_lattice_grid(CosetLattice::bcc(), LatticeVolume<double>::kMaxSize, 1),
               std::invalid_argument);
}

// The output grid of a lattice that no volume gives, the same for the CLI and Python: a spacing
// is taken as it is; a count N gives about N^3 samples (here N = 10 on BCC over [0,2]^3: no
// spacing 25% finer or coarser comes nearer 1000).
TEST(LatticeGridFor, ASpacingOrAboutNCubedSamples) {
  const CosetLattice bcc = CosetLattice::bcc();
  const Box box{{0, 0, 0}, {2, 2, 2}};
  const LatticeGrid given = lattice_grid_for(bcc, box, 0.25, 10);
  EXPECT_EQ(given.h, 0.25);
  const LatticeGrid counted = lattice_grid_for(bcc, box, std::nullopt, 10);
  const std::uint64_t samples =
      static_cast<std::uint64_t>(bcc.coset_count()) * static_cast<std::uint64_t>(counted.sizes[0]) *
      static_cast<std::uint64_t>(counted.sizes[1]) * static_cast<std::uint64_t>(counted.sizes[2]);
  EXPECT_EQ(samples, lattice_grid_count(bcc, box, counted.h));
  EXPECT_GT(samples, 500u);
  EXPECT_LT(samples, 2000u);
  for (double other : {0.8 * counted.h, 1.25 * counted.h}) {
    const std::int64_t off = static_cast<std::int64_t>(lattice_grid_count(bcc, box, other)) - 1000;
    EXPECT_GE(std::abs(off), std::abs(static_cast<std::int64_t>(samples) - 1000)) << other;
  }
  EXPECT_THROW(lattice_grid_for(bcc, box, 0.0, 10), std::invalid_argument);
}

}  // namespace
}  // namespace boxgen::runtime
