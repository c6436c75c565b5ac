// Resampling onto a Cartesian grid: cubic reproduction against the analytic polynomial, the grid
// geometry, the NRRD file as Teem reads it, the default box (inside the volume, and tight) and
// the errors for bad boxes.
#include "runtime/resample.h"
#include "runtime/reconstruction.h"

#include <gtest/gtest.h>
#include <teem/biff.h>
#include <teem/nrrd.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>

#include "generated/m12.hpp"
#include "generated/m7.hpp"
#include "generated/m8.hpp"
#include "runtime/affine.h"
#include "runtime/nrrd_io.h"
#include "runtime/prefilter.h"
#include "runtime/sampling.h"
#include "tests/support/bcc_volumes.h"
#include "tests/support/scratch_directory.h"

namespace boxgen::runtime {
namespace {

namespace fs = std::filesystem;

const SplineFilter kFilters[] = {SplineFilter::parse("m7"), SplineFilter::parse("m8"),
                                 SplineFilter::parse("m12")};

// A cubic with every kind of cubic term and no symmetry, written here rather than taken from
// runtime/test_functions so the expected values do not come from the code under test.
double cubic(const Vec3& p) {
  const double x = p[0], y = p[1], z = p[2];
  return 0.75 - 1.5 * x + 0.5 * y + 2 * z * z - 3 * x * y * z + x * x * x - 0.25 * y * y * z +
         1.25 * x * z * z - 0.5 * y * y * y;
}

template <class T>
LatticeVolume<T> prefiltered(const ScalarFunction& f, int n, const SplineFilter& filter,
                             PrefilterChoice q) {
  LatticeVolume<T> volume = test::sample_bcc_cube<T>(f, n, filter.required_margin(q));
  return q == PrefilterChoice::None ? volume : prefilter(volume, filter.prefilter(q));
}

double max_cubic_error(const CartesianVolume<double>& grid) {
  double worst = 0;
  for (int k = 0; k < grid.sizes[2]; ++k)
    for (int j = 0; j < grid.sizes[1]; ++j)
      for (int i = 0; i < grid.sizes[0]; ++i)
        worst = std::max(
            worst, std::abs(grid.values[grid.index(i, j, k)] - cubic(grid.position(i, j, k))));
  return worst;
}

TEST(Resample, CubicIsReproducedOnTheCartesianGridWithQ1) {
  // Quasi-interpolation of order 4 (Q^I) reproduces cubics: every grid value is the polynomial
  // at the grid point up to rounding. Without a prefilter it is not (so this test can fail).
  // The grid [-1,1]^3 with 7 points per axis puts points on lattice points, cell faces and inside.
  const CartesianGrid grid = grid_over({{-1, -1, -1}, {1, 1, 1}}, {7, 7, 7});
  for (const SplineFilter& f : kFilters) {
    const auto with_q1 = resample(prefiltered<double>(cubic, 9, f, PrefilterChoice::Q1), f, grid);
    EXPECT_LE(max_cubic_error(with_q1), 1e-11) << f.name();
    const auto without = resample(prefiltered<double>(cubic, 9, f, PrefilterChoice::None), f, grid);
    EXPECT_GT(max_cubic_error(without), 1e-4) << f.name();
  }
}

TEST(Resample, FloatVolumesResampleToFloatGrids) {
  // float data: the cubic (|values| <= about 8) to float rounding, 1e-5.
  const CartesianGrid grid = grid_over({{-1, -1, -1}, {1, 1, 1}}, {5, 5, 5});
  const auto values =
      resample(prefiltered<float>(cubic, 9, SplineFilter::parse("m8"), PrefilterChoice::Q1),
               SplineFilter::parse("m8"), grid);
  ASSERT_EQ(values.values.size(), 125u);
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i)
        EXPECT_NEAR(values.values[values.index(i, j, k)], cubic(values.position(i, j, k)), 1e-5)
            << i << " " << j << " " << k;
}

TEST(Resample, GridGeometryIsWhatWasAsked) {
  const Box box{{-1, -0.5, 0}, {1, 0.5, 0.75}};
  const CartesianGrid grid = grid_over(box, {5, 3, 4});
  EXPECT_EQ(grid.sizes, (Sizes{5, 3, 4}));
  EXPECT_EQ(grid.spacing, (Vec3{0.5, 0.5, 0.25}));
  EXPECT_EQ(grid.origin, (Vec3{-1, -0.5, 0}));

  const LatticeVolume<double> volume =
      prefiltered<double>(cubic, 9, SplineFilter::parse("m7"), PrefilterChoice::Q2);
  const auto out = resample(volume, SplineFilter::parse("m7"), grid);
  EXPECT_EQ(out.sizes, grid.sizes);
  EXPECT_EQ(out.spacing, grid.spacing);
  EXPECT_EQ(out.origin, grid.origin);
  ASSERT_EQ(out.values.size(), 60u);
  // The last point is the box's upper corner; storage is x fastest (index = i + 5 (j + 3 k)).
  EXPECT_EQ(out.position(4, 2, 3), box.max);
  const Reconstructor<double> r(volume, SplineFilter::parse("m7"));
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 5; ++i) {
        const Vec3 p{-1 + 0.5 * i, -0.5 + 0.5 * j, 0.25 * k};
        EXPECT_EQ(out.values[static_cast<std::size_t>(i + 5 * (j + 3 * k))], r.value(p))
            << i << " " << j << " " << k;
      }
}

TEST(Resample, AffineInverseAndCompositionAreExact) {
  // A rotation-and-shear with a translation: inverse().after(a) is the identity to rounding, and
  // after() applies the first map first (checked on a point by hand).
  Affine a;
  a.linear = {Vec3{0.8, -0.6, 0.1}, Vec3{0.6, 0.8, 0.0}, Vec3{0.0, 0.2, 1.5}};
  a.translation = {3, -2, 0.5};
  const Affine id = a.inverse().after(a);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(id.linear[r][c], r == c ? 1 : 0, 1e-15);
    EXPECT_NEAR(id.translation[r], 0, 1e-15);
  }
  const Affine shift = Affine::diagonal({2, 2, 2}, {1, 0, 0});  // x -> 2 x + (1, 0, 0)
  const Vec3 p = a.after(shift).apply({1, 1, 1});               // a((3, 2, 2))
  const Vec3 expected{3 + 0.8 * 3 - 0.6 * 2 + 0.1 * 2, -2 + 0.6 * 3 + 0.8 * 2, 0.5 + 0.2 * 2 + 3};
  for (int r = 0; r < 3; ++r) EXPECT_NEAR(p[r], expected[r], 1e-14) << r;
  Affine singular;
  singular.linear = {Vec3{1, 2, 3}, Vec3{2, 4, 6}, Vec3{0, 0, 1}};
  EXPECT_THROW((void)singular.inverse(), std::invalid_argument);
}

TEST(Resample, GridPointsMapIntoTheVolumesFrame) {
  // A grid with to_volume (an oblique grid or volume): each value is the spline at the mapped
  // point, computed here by the Reconstructor; a grid whose mapped corner leaves the region is
  // refused although its unmapped points lie inside.
  const SplineFilter f = SplineFilter::parse("m8");
  const LatticeVolume<double> volume = prefiltered<double>(cubic, 9, f, PrefilterChoice::Q1);
  CartesianGrid grid = grid_over({{-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}}, {4, 3, 5});
  Affine turn;  // 30 degrees about z, then a shift
  turn.linear = {Vec3{std::sqrt(3.0) / 2, -0.5, 0}, Vec3{0.5, std::sqrt(3.0) / 2, 0},
                 Vec3{0, 0, 1}};
  turn.translation = {0.1, -0.2, 0.3};
  grid.to_volume = turn;
  const auto out = resample(volume, f, grid);
  const Reconstructor<double> r(volume, f);
  double worst = 0;
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 4; ++i) {
        const Vec3 p = turn.apply(out.position(i, j, k));
        EXPECT_EQ(out.values[out.index(i, j, k)], r.value(p)) << i << " " << j << " " << k;
        worst = std::max(worst, std::abs(out.values[out.index(i, j, k)] - cubic(p)));
      }
  EXPECT_LE(worst, 1e-11);  // Q1 reproduces the cubic at the mapped points
  const Box region = evaluable_region(volume, f);
  CartesianGrid far = grid_over({region.min, region.max}, {3, 3, 3});
  far.spacing = {(region.max[0] - region.min[0]) / 2.5, (region.max[1] - region.min[1]) / 2.5,
                 (region.max[2] - region.min[2]) / 2.5};
  EXPECT_NO_THROW((void)resample(volume, f, far));
  far.to_volume = turn;  // the turned corners leave the box
  EXPECT_THROW((void)resample(volume, f, far), std::out_of_range);
}

TEST(Resample, BlocksHoldTheWholeGridsValuesBitForBit) {
  // A grid whose spacing is not a binary fraction: a block that recomputed its own origin and
  // spacing would round differently. Blocks tiling the grid (uneven sizes, a one-point block)
  // must give exactly the whole grid's values, at the whole grid's points.
  const CartesianGrid grid = grid_over({{-0.9, -0.7, -0.3}, {0.8, 0.6, 0.7}}, {7, 6, 5});
  const SplineFilter m7 = SplineFilter::parse("m7");
  const LatticeVolume<double> volume = prefiltered<double>(cubic, 9, m7, PrefilterChoice::Q2);
  const auto whole = resample(volume, m7, grid);
  const int cuts[3][3] = {{0, 3, 7}, {0, 5, 6}, {0, 2, 5}};
  for (int bi = 0; bi < 2; ++bi)
    for (int bj = 0; bj < 2; ++bj)
      for (int bk = 0; bk < 2; ++bk) {
        const GridBlock block{{cuts[0][bi], cuts[1][bj], cuts[2][bk]},
                              {cuts[0][bi + 1], cuts[1][bj + 1], cuts[2][bk + 1]}};
        const auto part = resample(volume, m7, grid, block);
        EXPECT_EQ(part.origin, whole.position(block.begin[0], block.begin[1], block.begin[2]));
        for (int k = 0; k < part.sizes[2]; ++k)
          for (int j = 0; j < part.sizes[1]; ++j)
            for (int i = 0; i < part.sizes[0]; ++i)
              ASSERT_EQ(part.values[part.index(i, j, k)],
                        whole.values[whole.index(block.begin[0] + i, block.begin[1] + j,
                                                 block.begin[2] + k)])
                  << bi << bj << bk << " " << i << " " << j << " " << k;
      }
  EXPECT_THROW(resample(volume, m7, grid, GridBlock{{0, 0, 0}, {8, 1, 1}}), std::invalid_argument);
  EXPECT_THROW(resample(volume, m7, grid, GridBlock{{2, 0, 0}, {2, 1, 1}}), std::invalid_argument);
}

class ResampleNrrd : public test::ScratchDirectoryTest {
 protected:
  ResampleNrrd() : ScratchDirectoryTest("boxgen-resample") {}
};

template <class T>
void expect_teem_reads(const fs::path& path, const CartesianVolume<T>& grid) {
  Nrrd* nrrd = nrrdNew();
  if (nrrdLoad(nrrd, path.c_str(), nullptr) != 0) {
    char* e = biffGetDone(NRRD);
    ADD_FAILURE() << "Teem cannot load " << path << ": " << e;
    std::free(e);
    nrrdNuke(nrrd);
    return;
  }
  EXPECT_EQ(nrrd->dim, 3u);
  EXPECT_EQ(nrrd->type, sizeof(T) == 8 ? nrrdTypeDouble : nrrdTypeFloat);
  EXPECT_EQ(nrrd->spaceDim, 3u);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(nrrd->axis[a].size, static_cast<std::size_t>(grid.sizes[a])) << a;
    for (int b = 0; b < 3; ++b)
      EXPECT_EQ(nrrd->axis[a].spaceDirection[b], a == b ? grid.spacing[a] : 0.0) << a << " " << b;
    EXPECT_EQ(nrrd->spaceOrigin[a], grid.origin[a]) << a;
  }
  ASSERT_NE(nrrd->data, nullptr);
  EXPECT_EQ(std::memcmp(nrrd->data, grid.values.data(), grid.values.size() * sizeof(T)), 0);
  nrrdNuke(nrrd);
}

TEST_F(ResampleNrrd, TeemReadsThePlain3dGrid) {
  // A box with no short decimal form: the header must carry the exact spacing and origin.
  const Box box{{-0.9, -1.0 / 3, 0.1}, {0.7, 0.8, 2.0 / 3}};
  const CartesianGrid grid = grid_over(box, {6, 5, 4});
  const auto d =
      resample(prefiltered<double>(cubic, 9, SplineFilter::parse("m12"), PrefilterChoice::Q1),
               SplineFilter::parse("m12"), grid);
  write_cartesian_nrrd(dir_ / "d.nrrd", d);
  expect_teem_reads(dir_ / "d.nrrd", d);
  const auto f =
      resample(prefiltered<float>(cubic, 9, SplineFilter::parse("m7"), PrefilterChoice::None),
               SplineFilter::parse("m7"), grid);
  write_cartesian_nrrd(dir_ / "f.nrrd", f);
  expect_teem_reads(dir_ / "f.nrrd", f);
}

// The generated evaluator's own view of its stencil: every lattice point it fetches, relative to
// floor(x + c), over many random points (a recording fetch, independent of the tables).
template <class Evaluate>
void expect_reach_matches_fetches(const SplineFilter& f, Evaluate evaluate) {
  const StencilReach reach = f.reach();
  std::array<int, 3> seen_lo{99, 99, 99}, seen_hi{-99, -99, -99};
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-4, 4);
  for (int n = 0; n < 20000; ++n) {
    const std::array<double, 3> x{u(rng), u(rng), u(rng)};
    evaluate(x, [&](const std::array<std::int64_t, 3>& j) {
      for (int a = 0; a < 3; ++a) {
        const int d =
            static_cast<int>(j[a] - static_cast<std::int64_t>(std::floor(x[a] + reach.centre[a])));
        seen_lo[a] = std::min(seen_lo[a], d);
        seen_hi[a] = std::max(seen_hi[a], d);
      }
      return 1.0;
    });
  }
  EXPECT_EQ(seen_lo, reach.lo) << f.name();
  EXPECT_EQ(seen_hi, reach.hi) << f.name();
}

TEST(Resample, StencilReachIsWhatTheEvaluatorsFetch) {
  expect_reach_matches_fetches(SplineFilter::parse("m7"), [](const auto& x, auto&& fetch) {
    return generated::m7::evaluate<double>(x, fetch);
  });
  expect_reach_matches_fetches(SplineFilter::parse("m8"), [](const auto& x, auto&& fetch) {
    return generated::m8::evaluate<double>(x, fetch);
  });
  expect_reach_matches_fetches(SplineFilter::parse("m12"), [](const auto& x, auto&& fetch) {
    return generated::m12::evaluate<double>(x, fetch);
  });
}

// Every point of the default grid, its corners and random points inside evaluate; a point one grid
// step (or just 1e-3 lattice units) beyond any of its six faces leaves the volume for some
// position on that face.
template <class T>
void expect_default_box_inside_and_tight(const LatticeVolume<T>& volume, const SplineFilter& f) {
  SCOPED_TRACE(::testing::Message() << f.name() << (sizeof(T) == 4 ? " float" : " double"));
  const Box box = default_box(volume, f);
  const int n = 9;
  const CartesianGrid grid = grid_over(box, {n, n, n});
  EXPECT_NO_THROW(resample(volume, f, grid));
  const Reconstructor<T> r(volume, f);
  // The box lies inside the volume's lattice range (0..2N-1, in world coordinates).
  for (int a = 0; a < 3; ++a) {
    EXPECT_GE(box.min[a], volume.origin()[a]);
    EXPECT_LE(box.max[a], volume.origin()[a] + volume.spacing() * (2 * volume.sizes()[a] - 1));
  }
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  for (int s = 0; s < 2000; ++s) {
    Vec3 p;
    for (int a = 0; a < 3; ++a)
      p[a] = s < 8 ? ((s >> a) & 1 ? box.max[a] : box.min[a])
                   : box.min[a] + u(rng) * (box.max[a] - box.min[a]);
    EXPECT_NO_THROW(r.value(p)) << p[0] << " " << p[1] << " " << p[2];
  }
  // Beyond a face by one grid step (the brief's test), and by only 1e-3 lattice units: the box
  // is tight to far less than a grid step (the rounding guard is below 1e-4 units).
  for (const double step : {grid.spacing[0], 1e-3 * volume.spacing()})
    for (int a = 0; a < 3; ++a)
      for (int side = 0; side < 2; ++side) {
        int outside = 0;
        const int b = (a + 1) % 3, c = (a + 2) % 3;
        for (int i = 0; i <= 40; ++i)
          for (int k = 0; k <= 40; ++k) {
            Vec3 p;
            p[a] = side ? box.max[a] + step : box.min[a] - step;
            p[b] = box.min[b] + (box.max[b] - box.min[b]) * i / 40;
            p[c] = box.min[c] + (box.max[c] - box.min[c]) * k / 40;
            try {
              (void)r.value(p);
            } catch (const std::out_of_range&) {
              ++outside;
            }
          }
        EXPECT_GT(outside, 0) << "the box could grow by " << step << " on axis " << a
                              << (side ? " upwards" : " downwards");
      }
}

TEST(Resample, DefaultBoxIsInsideTheVolumeAndTight) {
  // Unequal sizes, an origin off zero and a spacing with no short binary form.
  for (const SplineFilter& f : kFilters) {
    LatticeVolume<double> d(CosetLattice::bcc(), {9, 10, 11}, 0.1, {0.3, -2, 5});
    LatticeVolume<float> s(CosetLattice::bcc(), {11, 9, 10}, 1.0 / 3, {-7, 0.25, 100});
    expect_default_box_inside_and_tight(d, f);
    expect_default_box_inside_and_tight(s, f);
  }
}

TEST(Resample, DefaultBoxOfASampledCubeHoldsTheCube) {
  // With required_margin (reconstruction.h) as the sampling margin, [-1,1]^3 is inside the default
  // box.
  for (const SplineFilter& f : kFilters)
    for (PrefilterChoice q : {PrefilterChoice::None, PrefilterChoice::Q2}) {
      const Box box = default_box(prefiltered<double>(cubic, 5, f, q), f);
      for (int a = 0; a < 3; ++a) {
        EXPECT_LE(box.min[a], -1) << f.name();
        EXPECT_GE(box.max[a], 1) << f.name();
      }
    }
}

TEST(Resample, BadBoxesAndGridsAreErrors) {
  const LatticeVolume<double> volume =
      prefiltered<double>(cubic, 5, SplineFilter::parse("m7"), PrefilterChoice::None);
  const Box inside{{-1, -1, -1}, {1, 1, 1}};
  // Empty, degenerate, inverted or non-finite boxes, and too few points.
  EXPECT_THROW(grid_over({{-1, 0, -1}, {1, 0, 1}}, {3, 3, 3}), std::invalid_argument);
  EXPECT_THROW(grid_over({{1, -1, -1}, {-1, 1, 1}}, {3, 3, 3}), std::invalid_argument);
  EXPECT_THROW(grid_over({{-1, -1, NAN}, {1, 1, 1}}, {3, 3, 3}), std::invalid_argument);
  EXPECT_THROW(grid_over({{-1, -1, -1}, {1, INFINITY, 1}}, {3, 3, 3}), std::invalid_argument);
  EXPECT_THROW(grid_over(inside, {3, 1, 3}), std::invalid_argument);
  EXPECT_THROW(grid_over(inside, {3, 3, kMaxGridSize + 1}), std::invalid_argument);
  EXPECT_THROW(grid_over(inside, {kMaxGridSize, kMaxGridSize, kMaxGridSize}),
               std::invalid_argument);
  // A grid with zero spacing or a non-finite origin.
  EXPECT_THROW(resample(volume, SplineFilter::parse("m7"),
                        CartesianGrid{{3, 3, 3}, {0.5, 0, 0.5}, {0, 0, 0}}),
               std::invalid_argument);
  EXPECT_THROW(resample(volume, SplineFilter::parse("m7"),
                        CartesianGrid{{3, 3, 3}, {0.5, 0.5, 0.5}, {0, NAN, 0}}),
               std::invalid_argument);
  // A box leaving the volume, on either side of any axis: one line naming the allowed region.
  const Box allowed = default_box(volume, SplineFilter::parse("m7"));
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      Box out = inside;
      (side ? out.max : out.min)[a] = side ? allowed.max[a] + 0.5 : allowed.min[a] - 0.5;
      try {
        (void)resample(volume, SplineFilter::parse("m7"), grid_over(out, {3, 3, 3}));
        ADD_FAILURE() << "a box leaving the volume on axis " << a << " was accepted";
      } catch (const std::out_of_range& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("m7"), std::string::npos) << e.what();
      }
    }
  // A volume too small for the stencil has no default box, and nothing can be resampled from it.
  const LatticeVolume<double> tiny(CosetLattice::bcc(), {2, 9, 9}, 0.5, {0, 0, 0});
  EXPECT_THROW((void)default_box(tiny, SplineFilter::parse("m8")), std::invalid_argument);
  EXPECT_THROW(
      (void)resample(tiny, SplineFilter::parse("m8"), grid_over({{1, 1, 1}, {2, 2, 2}}, {3, 3, 3})),
      std::invalid_argument);
}

}  // namespace
}  // namespace boxgen::runtime
