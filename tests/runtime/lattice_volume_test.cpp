// Volumes on any lattice (runtime/coset_lattice.h, lattice_volume.h, and their sampling,
// prefiltering and NRRD files). Oracles: the decompositions the issue states for BCC, FCC and
// Cartesian; for custom lattices, brute-force enumeration of G z; the BCC code paths, which must
// agree bit for bit on BCC; direct convolution through value().
#include <gtest/gtest.h>
#include <teem/biff.h>
#include <teem/nrrd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <random>
#include <set>
#include <sstream>

#include "runtime/nrrd_io.h"
#include "runtime/prefilter.h"
#include "runtime/reconstruction.h"
#include "runtime/sampling.h"
#include "tests/support/bcc_volumes.h"
#include "tests/support/scratch_directory.h"
#include "tests/support/volume_expectations.h"

namespace boxgen::runtime {
namespace {

namespace fs = std::filesystem;
using Point = std::array<std::int64_t, 3>;

// Every point G z, z in [-r, r]^3.
std::set<Point> enumerate(const IntRows& g, int r) {
  std::set<Point> points;
  for (int a = -r; a <= r; ++a)
    for (int b = -r; b <= r; ++b)
      for (int c = -r; c <= r; ++c)
        points.insert({g[0][0] * a + g[0][1] * b + g[0][2] * c,
                       g[1][0] * a + g[1][1] * b + g[1][2] * c,
                       g[2][0] * a + g[2][1] * b + g[2][2] * c});
  return points;
}

TEST(CosetLattice, NamedLatticesAreAsSpecified) {
  const CosetLattice bcc = CosetLattice::bcc(), fcc = CosetLattice::fcc(),
                     cart = CosetLattice::cartesian();
  EXPECT_EQ(bcc.period(), 2);
  EXPECT_EQ(bcc.coset_count(), 2);
  EXPECT_EQ(bcc.offsets(), (std::vector<Offset>{{0, 0, 0}, {1, 1, 1}}));
  EXPECT_EQ(fcc.period(), 2);
  EXPECT_EQ(fcc.coset_count(), 4);
  EXPECT_EQ(fcc.offsets(), (std::vector<Offset>{{0, 0, 0}, {1, 1, 0}, {1, 0, 1}, {0, 1, 1}}));
  EXPECT_EQ(cart.period(), 1);
  EXPECT_EQ(cart.offsets(), (std::vector<Offset>{{0, 0, 0}}));
  EXPECT_EQ(bcc.offsets_text(), "(0,0,0) (1,1,1)");
  EXPECT_EQ(CosetLattice::parse("bcc"), bcc);
  EXPECT_EQ(CosetLattice::parse(" fcc "), fcc);
  // Membership: BCC all even or all odd, FCC an even coordinate sum.
  for (int x = -3; x <= 3; ++x)
    for (int y = -3; y <= 3; ++y)
      for (int z = -3; z <= 3; ++z) {
        EXPECT_EQ(bcc.contains(x, y, z), ((x - y) % 2 == 0 && (x - z) % 2 == 0));
        EXPECT_EQ(fcc.contains(x, y, z), (x + y + z) % 2 == 0);
        EXPECT_TRUE(cart.contains(x, y, z));
      }
}

struct CustomCase {
  const char* rows;
  const char* name;  // what from_rows recognizes
  int d;             // expected, derived by hand
  int k;
};

TEST(CosetLattice, CustomLatticesAgreeWithEnumeration) {
  const std::vector<CustomCase> cases = {
      {"1,0,0; 0,1,0; 0,0,3", "custom", 3, 9},   // z = 0 (mod 3)
      {"2,1,0; 0,1,0; 0,0,1", "custom", 2, 4},   // x = y (mod 2)
      {"1,1,0; 1,-1,0; 0,0,1", "custom", 2, 4},  // x + y even, z free
      {"2,0,1; 0,2,1; 0,0,1", "bcc", 2, 2},      // columns (2,0,0) (0,2,0) (1,1,1): BCC
      {"0,1,1; 1,0,1; 1,1,0", "fcc", 2, 4},      // FCC with its columns permuted
      {"-1,0,0; 0,1,0; 0,0,-1", "cartesian", 1, 1},
      {"2,0,0; 0,2,0; 0,0,2", "custom", 2, 1},  // 2 Z^3
  };
  for (const CustomCase& c : cases) {
    SCOPED_TRACE(c.rows);
    const CosetLattice l = CosetLattice::parse(c.rows);
    EXPECT_EQ(l.name(), c.name);
    EXPECT_EQ(l.period(), c.d);
    EXPECT_EQ(l.coset_count(), c.k);
    const std::set<Point> points = enumerate(l.rows(), 8);
    // d: the smallest integer whose multiples of the unit vectors are lattice points.
    int d = 1;
    while (!(points.count({d, 0, 0}) && points.count({0, d, 0}) && points.count({0, 0, d}))) ++d;
    EXPECT_EQ(l.period(), d);
    // Every offset is a lattice point; the offsets are one per coset of d Z^3; membership agrees.
    std::set<Point> residues;
    for (const Offset& o : l.offsets()) {
      EXPECT_TRUE(points.count({o[0], o[1], o[2]})) << o[0] << " " << o[1] << " " << o[2];
      residues.insert({((o[0] % d) + d) % d, ((o[1] % d) + d) % d, ((o[2] % d) + d) % d});
    }
    EXPECT_EQ(residues.size(), l.offsets().size());
    for (int x = -4; x <= 4; ++x)
      for (int y = -4; y <= 4; ++y)
        for (int z = -4; z <= 4; ++z)
          EXPECT_EQ(l.contains(x, y, z), points.count({x, y, z}) == 1) << x << " " << y << " " << z;
    // The text forms round-trip.
    EXPECT_EQ(CosetLattice::parse(l.rows_text()), l);
  }
}

// The generator's spellings (support/lattice_text.h): names in any case, blanks or commas, a
// trailing ';', rows over several lines.
TEST(CosetLattice, ParsesEverySpellingTheGeneratorTakes) {
  EXPECT_EQ(CosetLattice::parse("BCC"), CosetLattice::bcc());
  EXPECT_EQ(CosetLattice::parse("\tFcc\n"), CosetLattice::fcc());
  EXPECT_EQ(CosetLattice::parse("Cartesian"), CosetLattice::cartesian());
  EXPECT_EQ(CosetLattice::parse("-1 1 1; 1 -1 1; 1 1 -1;"), CosetLattice::bcc());
  const CosetLattice custom = CosetLattice::parse("1,0,0; 0,1,0; 0,0,3");
  EXPECT_EQ(CosetLattice::parse("1 0 0;\n0, 1, 0;\n+0 0 3;"), custom);
  EXPECT_EQ(custom.name(), "custom");
  try {
    (void)CosetLattice::parse("1,0; 0,1");
    ADD_FAILURE() << "a 2-D lattice was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "the lattice is 2-dimensional but volumes are 3-D");
  }
}

TEST(CosetLattice, BadLatticesAreOneLineErrors) {
  for (const char* text :
       {"1,0,0; 0,1,0; 1,1,0", "1,0,0; 0,1,0", "1,0,0; 0,1,0; 0,0,x", "1,0; 0,1; 0,0", "hex", "",
        "1,0,0; 0,1,0; 0,0,65", "1,0,0; 0,1,0; 0,0,9999999999"}) {
    try {
      (void)CosetLattice::parse(text);
      ADD_FAILURE() << text << ": no error";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  }
  const CosetLattice fcc = CosetLattice::fcc();
  EXPECT_THROW((void)fcc.with_offsets({{0, 0, 0}, {1, 1, 0}, {1, 0, 1}}),
               std::invalid_argument);  // too few
  EXPECT_THROW((void)fcc.with_offsets({{0, 0, 0}, {1, 1, 0}, {1, 0, 1}, {1, 1, 1}}),
               std::invalid_argument);  // not in L
  EXPECT_THROW((void)fcc.with_offsets({{0, 0, 0}, {1, 1, 0}, {1, 0, 1}, {2, 2, 0}}),
               std::invalid_argument);  // same coset
  const CosetLattice moved = fcc.with_offsets({{0, 1, 1}, {0, 0, 0}, {3, 1, 0}, {1, 0, 1}});
  EXPECT_EQ(moved.coset_of(1, 1, 0), 2);
  EXPECT_EQ(moved.coset_of(2, 1, 1), 0);
}

std::vector<CosetLattice> all_lattices() {
  return {CosetLattice::bcc(), CosetLattice::fcc(), CosetLattice::cartesian(),
          CosetLattice::parse("1,0,0; 0,1,0; 0,0,3"),
          CosetLattice::fcc().with_offsets({{0, 1, 1}, {0, 0, 0}, {3, 1, 0}, {1, 0, 1}})};
}

// Fills v (sizes 3 x 2 x 4, spacing 0.5, origin (1, -2, 0.25)) sample by sample, checking the
// storage order, the lattice point and the world position of each; returns the points held.
std::set<Point> fill_and_check_layout(LatticeVolume<double>& v, const CosetLattice& lattice) {
  const int k = lattice.coset_count(), d = lattice.period();
  std::set<Point> held;
  double next = 1;
  for (int kk = 0; kk < 4; ++kk)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i)
        for (int c = 0; c < k; ++c) {
          EXPECT_EQ(v.index(c, i, j, kk), static_cast<std::size_t>(c + k * (i + 3 * (j + 2 * kk))));
          v.at(c, i, j, kk) = next++;
          const Offset& o = lattice.offsets()[static_cast<std::size_t>(c)];
          const Point p{o[0] + d * i, o[1] + d * j, o[2] + d * kk};
          EXPECT_EQ(v.lattice_point(c, i, j, kk), p);
          EXPECT_EQ(v.sample_position(c, i, j, kk),
                    (Vec3{1 + 0.5 * static_cast<double>(p[0]), -2 + 0.5 * static_cast<double>(p[1]),
                          0.25 + 0.5 * static_cast<double>(p[2])}));
          held.insert(p);
        }
  for (int kk = 0; kk < 4; ++kk)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i)
        for (int c = 0; c < k; ++c)
          EXPECT_EQ(v.value(v.lattice_point(c, i, j, kk)), v.at(c, i, j, kk));
  return held;
}

// contains() is exactly the held points; value() throws elsewhere, value_or() does not.
void check_contains(const LatticeVolume<double>& v, const std::set<Point>& held) {
  for (std::int64_t x = -4; x <= 12; ++x)
    for (std::int64_t y = -4; y <= 8; ++y)
      for (std::int64_t z = -4; z <= 14; ++z) {
        const bool inside = held.count({x, y, z}) == 1;
        ASSERT_EQ(v.contains(x, y, z), inside) << x << " " << y << " " << z;
        if (!inside) {
          EXPECT_THROW((void)v.value(x, y, z), std::out_of_range);
          EXPECT_EQ(v.value_or(x, y, z, -1.0), -1.0);
        }
      }
}

// contains_box() against the lattice points of random boxes.
void check_contains_box(const LatticeVolume<double>& v, const CosetLattice& lattice,
                        const std::set<Point>& held) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> coordinate(-3, 14);
  for (int trial = 0; trial < 400; ++trial) {
    Point lo, hi;
    for (int a = 0; a < 3; ++a) {
      lo[a] = coordinate(rng);
      hi[a] = lo[a] + coordinate(rng) % 5;
    }
    bool all = true;
    for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
        for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
          if (lattice.contains(x, y, z) && !held.count({x, y, z})) all = false;
    EXPECT_EQ(v.contains_box(lo, hi), all)
        << lo[0] << " " << lo[1] << " " << lo[2] << " .. " << hi[0] << " " << hi[1] << " " << hi[2];
  }
}

TEST(LatticeVolume, StorageAndLatticeAccessAgree) {
  for (const CosetLattice& lattice : all_lattices()) {
    SCOPED_TRACE(lattice.name() + " " + lattice.offsets_text());
    LatticeVolume<double> v(lattice, {3, 2, 4}, 0.5, {1, -2, 0.25});
    const int k = lattice.coset_count();
    ASSERT_EQ(v.sample_count(), static_cast<std::size_t>(k * 3 * 2 * 4));
    const std::set<Point> held = fill_and_check_layout(v, lattice);
    check_contains(v, held);
    check_contains_box(v, lattice, held);
    EXPECT_THROW((void)v.at(k, 0, 0, 0), std::out_of_range);
  }
  EXPECT_THROW(LatticeVolume<float>(CosetLattice::fcc(), {0, 1, 1}, 1, {0, 0, 0}),
               std::invalid_argument);
  EXPECT_THROW(LatticeVolume<float>(CosetLattice::fcc(), {1, 1, 1}, 0, {0, 0, 0}),
               std::invalid_argument);
  EXPECT_THROW(
      LatticeVolume<float>(CosetLattice::fcc(), {1, 1, 1}, 1, {0, 0, 0}, std::vector<float>(3)),
      std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// Sampling

double smooth(const Vec3& p) { return std::sin(p[0]) + p[1] * p[1] - 0.5 * p[2] + p[0] * p[2]; }

// On BCC the grid is docs/design.md §13's: h = 1/(N-1), origin -1 - 2 h m, sample (c, i, j, k) at
// o + h (2i + c, 2j + c, 2k + c), every value f there exactly.
TEST(LatticeSampling, OnBccItIsTheDesignsGridBitForBit) {
  const LatticeVolume<double> l =
      sample_lattice<double>(smooth, cube_lattice_grid(CosetLattice::bcc(), 7, 2));
  const double h = 1.0 / 6;
  EXPECT_EQ(l.sizes(), (Sizes{11, 11, 11}));
  EXPECT_EQ(l.spacing(), h);
  EXPECT_EQ(l.origin(), (Vec3{-1 - 2 * h * 2, -1 - 2 * h * 2, -1 - 2 * h * 2}));
  const double o = -1 - 2 * h * 2;
  for (int k = 0; k < 11; ++k)
    for (int j = 0; j < 11; ++j)
      for (int i = 0; i < 11; ++i)
        for (int c = 0; c < 2; ++c)
          ASSERT_EQ(l(c, i, j, k),
                    smooth({o + h * (2 * i + c), o + h * (2 * j + c), o + h * (2 * k + c)}));
}

TEST(LatticeSampling, EverySampleIsTheFunctionAtItsLatticePoint) {
  for (const CosetLattice& lattice : all_lattices()) {
    SCOPED_TRACE(lattice.name());
    const LatticeGrid grid = cube_lattice_grid(lattice, 5, 1);
    const double cell = 2.0 / 4;  // d h = 2/(N-1)
    EXPECT_DOUBLE_EQ(grid.h * lattice.period(), cell);
    EXPECT_EQ(grid.sizes, (Sizes{7, 7, 7}));
    const LatticeVolume<float> v = sample_lattice<float>(smooth, grid);
    for (int k = 0; k < 7; ++k)
      for (int j = 0; j < 7; ++j)
        for (int i = 0; i < 7; ++i)
          for (int c = 0; c < lattice.coset_count(); ++c) {
            const Offset& o = lattice.offsets()[static_cast<std::size_t>(c)];
            const Vec3 p{-1 - cell + grid.h * (o[0] + lattice.period() * i),
                         -1 - cell + grid.h * (o[1] + lattice.period() * j),
                         -1 - cell + grid.h * (o[2] + lattice.period() * k)};
            EXPECT_FLOAT_EQ(v(c, i, j, k), static_cast<float>(smooth(p)));
          }
    // Coset cells of the cube [-1,1]^3: the sample (c=0 with offset 0, i = margin) sits at -1.
    if (lattice.offsets()[0] == Offset{0, 0, 0}) {
      EXPECT_DOUBLE_EQ(v.sample_position(0, 1, 1, 1)[0], -1.0);
    }
  }
  EXPECT_THROW((void)cube_lattice_grid(CosetLattice::fcc(), 1, 0), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// Prefiltering

// On BCC the result loses ceil(max o_a / 2) coset cells below and ceil(-min o_a / 2) above, and
// each sample is the taps' sum in double, in the taps' order, of the input read through value().
TEST(LatticePrefilter, OnBccItIsTheBccPrefilterBitForBit) {
  const LatticeVolume<double> b = test::sample_bcc_cube<double>(smooth, 6, 2);
  const PrefilterTaps q = {{{0, 0, 0}, 2.0},
                           {{1, 1, 1}, -0.125},
                           {{-1, 1, -1}, -0.125},
                           {{2, 0, 0}, 0.0625},
                           {{0, -2, 0}, 0.25}};
  const LatticeVolume<double> got = prefilter(b, q);
  // x: offsets up to 2 and down to -1, y: 1 and -2, z: 1 and -1: one cell each side.
  EXPECT_EQ(got.sizes(), (Sizes{b.sizes()[0] - 2, b.sizes()[1] - 2, b.sizes()[2] - 2}));
  for (int a = 0; a < 3; ++a) EXPECT_EQ(got.origin()[a], b.origin()[a] + 2 * b.spacing());
  for (int k = 0; k < got.sizes()[2]; ++k)
    for (int j = 0; j < got.sizes()[1]; ++j)
      for (int i = 0; i < got.sizes()[0]; ++i)
        for (int c = 0; c < 2; ++c) {
          const LatticePoint x = b.lattice_point(c, i + 1, j + 1, k + 1);
          double sum = 0;
          for (const auto& [o, w] : q) sum += w * b.value(x[0] - o[0], x[1] - o[1], x[2] - o[2]);
          ASSERT_EQ(got(c, i, j, k), sum);
        }
}

TEST(LatticePrefilter, IsTheConvolutionOnEveryLattice) {
  for (const CosetLattice& lattice : all_lattices()) {
    SCOPED_TRACE(lattice.name() + " " + lattice.offsets_text());
    const LatticeVolume<double> v =
        sample_lattice<double>(smooth, cube_lattice_grid(lattice, 6, 2));
    // Taps: the origin and lattice points near it, with weights of no special form.
    PrefilterTaps q;
    double w = 0.5;
    for (int x = -2; x <= 2; ++x)
      for (int y = -2; y <= 2; ++y)
        for (int z = -1; z <= 3; ++z)
          if (lattice.contains(x, y, z) && std::abs(x) + std::abs(y) + std::abs(z) <= 3) {
            q.push_back({{x, y, z}, w});
            w = -w * 0.75 + 0.01;
          }
    const LatticeVolume<double> out = prefilter(v, q);
    // Every output sample is the sum over taps of v at j - o, read through value(), at the same
    // world point.
    std::size_t checked = 0;
    for (int k = 0; k < out.sizes()[2]; ++k)
      for (int j = 0; j < out.sizes()[1]; ++j)
        for (int i = 0; i < out.sizes()[0]; ++i)
          for (int c = 0; c < out.coset_count(); ++c) {
            const Vec3 world = out.sample_position(c, i, j, k);
            const Vec3 l = v.to_lattice(world);
            const Point p{std::llround(l[0]), std::llround(l[1]), std::llround(l[2])};
            double sum = 0;
            for (const auto& [o, weight] : q)
              sum += weight * v.value(p[0] - o[0], p[1] - o[1], p[2] - o[2]);
            EXPECT_NEAR(out(c, i, j, k), sum, 1e-13) << c << " " << i << " " << j << " " << k;
            ++checked;
          }
    EXPECT_GT(checked, 0u);
    // The result is the largest such volume: one more sample on any side would need data outside.
    const PrefilterShrink s = prefilter_shrink(q, lattice);
    for (int a = 0; a < 3; ++a) EXPECT_EQ(out.sizes()[a], v.sizes()[a] - s.lower[a] - s.upper[a]);
    PrefilterTaps off_lattice = q;
    off_lattice.push_back({{1, 0, 0}, 1.0});
    if (!lattice.contains(1, 0, 0)) {
      EXPECT_THROW((void)prefilter(v, off_lattice), std::invalid_argument);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// NRRD files

class LatticeNrrd : public test::ScratchDirectoryTest {
 protected:
  LatticeNrrd() : ScratchDirectoryTest("boxgen-lattice") {}
  fs::path file(const std::string& name) const { return dir_ / name; }
};

template <class T>
LatticeVolume<T> random_volume(const CosetLattice& lattice, Sizes sizes, unsigned seed) {
  LatticeVolume<T> v(lattice, sizes, 1.0 / 7, {-0.3, 1.0 / 3, 2e5},
                     std::vector<T>(static_cast<std::size_t>(lattice.coset_count()) * sizes[0] *
                                    sizes[1] * sizes[2]));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  for (T& x : v.samples())
    x = static_cast<T>(std::ldexp(u(rng), static_cast<int>(rng() % 40) - 20));
  return v;
}

using test::expect_identical;

std::string key(const Nrrd* nrrd, const char* name) {
  char* v = nrrdKeyValueGet(nrrd, name);
  std::string s = v ? v : "<missing>";
  std::free(v);
  return s;
}

TEST_F(LatticeNrrd, RoundTripsOnEveryLattice) {
  unsigned seed = 1;
  for (const CosetLattice& lattice : all_lattices()) {
    SCOPED_TRACE(lattice.name() + " " + lattice.offsets_text());
    const auto d = random_volume<double>(lattice, {3, 2, 4}, seed++);
    write_lattice_nrrd(file("d.nrrd"), d);
    expect_identical(read_lattice_nrrd<double>(file("d.nrrd")), d);
    const auto f = random_volume<float>(lattice, {1, 5, 2}, seed++);
    write_lattice_nrrd(file("f.nrrd"), f);
    expect_identical(read_lattice_nrrd<float>(file("f.nrrd")), f);

    // The header as Teem sees it.
    Nrrd* nrrd = nrrdNew();
    ASSERT_EQ(nrrdLoad(nrrd, file("d.nrrd").c_str(), nullptr), 0);
    const int k = lattice.coset_count();
    const unsigned first = k == 1 ? 0 : 1;
    EXPECT_EQ(nrrd->dim, 3 + first);
    if (first) {
      EXPECT_EQ(nrrd->axis[0].size, static_cast<std::size_t>(k));
    }
    EXPECT_EQ(nrrd->axis[first].size, 3u);
    EXPECT_EQ(nrrd->axis[first + 2].size, 4u);
    for (unsigned a = 0; a < 3; ++a)
      for (unsigned b = 0; b < 3; ++b)
        EXPECT_DOUBLE_EQ(nrrd->axis[first + a].spaceDirection[b],
                         a == b ? lattice.period() / 7.0 : 0.0);
    EXPECT_EQ(key(nrrd, "lattice"), lattice.name());
    if (lattice.name() == "custom") {
      EXPECT_EQ(key(nrrd, "lattice_rows"), "1,0,0; 0,1,0; 0,0,3");
      EXPECT_EQ(key(nrrd, "coset_offsets").substr(0, 24), "(0,0,0) (1,0,0) (2,0,0) ");
    } else {
      EXPECT_EQ(key(nrrd, "lattice_rows"), "<missing>");
      // Offsets only when the cosets are not in the named lattice's own order.
      EXPECT_EQ(key(nrrd, "coset_offsets"), lattice == CosetLattice::parse(lattice.name())
                                                ? "<missing>"
                                                : lattice.offsets_text());
    }
    nrrdNuke(nrrd);
  }
}

TEST_F(LatticeNrrd, BccFilesAreLatticeFilesAndBack) {
  LatticeVolume<double> b(CosetLattice::bcc(), {2, 3, 2}, 0.125, {1, 2, 3});
  for (std::size_t s = 0; s < b.sample_count(); ++s)
    b.samples()[s] = std::sqrt(static_cast<double>(s) + 0.5);
  write_lattice_nrrd(file("b.nrrd"), b);
  const LatticeVolume<double> l = read_lattice_nrrd<double>(file("b.nrrd"));
  expect_identical(l, b);
  write_lattice_nrrd(file("l.nrrd"), l);
  const LatticeVolume<double> again = read_lattice_nrrd<double>(file("l.nrrd"));
  EXPECT_EQ(std::memcmp(again.samples().data(), b.samples().data(), b.samples().size_bytes()), 0);
  // Written again, the same bytes; a BCC file is the layout of nrrd_io.h (no coset_offsets key
  // for the offsets (0,0,0) (1,1,1)).
  std::ifstream x(file("b.nrrd"), std::ios::binary), y(file("l.nrrd"), std::ios::binary);
  std::stringstream bx, by;
  bx << x.rdbuf();
  by << y.rdbuf();
  EXPECT_EQ(bx.str(), by.str());
  const std::string header = bx.str().substr(0, bx.str().find("\n\n") + 1);
  for (const char* field : {"dimension: 4\n", "sizes: 2 2 3 2\n",
                            "space directions: none (0.25,0,0) (0,0.25,0) (0,0,0.25)\n",
                            "space origin: (1,2,3)\n", "lattice:=bcc\n"})
    EXPECT_NE(header.find(field), std::string::npos) << field << " in " << header;
  EXPECT_EQ(header.find("coset_offsets"), std::string::npos) << header;
  // An FCC file is no BCC volume: no BCC filter takes it.
  write_lattice_nrrd(file("fcc.nrrd"), random_volume<double>(CosetLattice::fcc(), {2, 2, 2}, 9));
  const LatticeVolume<double> fcc = read_lattice_nrrd<double>(file("fcc.nrrd"));
  EXPECT_EQ(fcc.lattice(), CosetLattice::fcc());
  EXPECT_THROW(Reconstructor<double>(fcc, SplineFilter::parse("m7")), std::invalid_argument);
}

TEST_F(LatticeNrrd, APlain3dNrrdIsACartesianVolume) {
  CartesianVolume<float> grid;
  grid.sizes = {3, 2, 2};
  grid.spacing = {0.5, 0.5, 0.5};
  grid.origin = {1, 0, -1};
  for (int s = 0; s < 12; ++s) grid.values.push_back(static_cast<float>(s));
  write_cartesian_nrrd(file("g.nrrd"), grid);
  const LatticeVolume<float> v = read_lattice_nrrd<float>(file("g.nrrd"));
  EXPECT_EQ(v.lattice().name(), "cartesian");
  EXPECT_EQ(v.spacing(), 0.5);
  EXPECT_EQ(v.value(2, 1, 1), 11.0f);
  EXPECT_EQ(v.sample_position(0, 2, 1, 1), (Vec3{2, 0.5, -0.5}));
}

TEST_F(LatticeNrrd, InconsistentLatticeHeadersAreRefused) {
  const auto v = random_volume<double>(CosetLattice::parse("1,0,0; 0,1,0; 0,0,3"), {2, 2, 2}, 3);
  write_lattice_nrrd(file("custom.nrrd"), v);
  std::ifstream in(file("custom.nrrd"), std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string good = buffer.str();
  auto with = [&](const std::string& from, const std::string& to) {
    std::string text = good;
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
  };
  const std::vector<std::pair<std::string, std::string>> cases = {
      {with("lattice_rows:=1,0,0; 0,1,0; 0,0,3\n", ""), "lattice_rows"},
      {with("coset_offsets:=", "coset_offset:="), "coset_offsets"},
      {with("(2,0,0)", "(2,0,1)"), "not a lattice point"},
      {with("(2,0,0)", "(1,0,0)"), "same coset"},
      {with("(2,0,0)", "[2,0,0]"), "coset_offsets"},
      {with("lattice:=custom", "lattice:=fcc"), "do not generate"},
      {with("lattice:=custom", "lattice:=hexagonal"), "hexagonal"},
      {with("0,0,3\n", "0,0,0\n"), "singular"},
  };
  for (const auto& [bytes, expected] : cases) {
    std::ofstream(file("bad.nrrd"), std::ios::binary) << bytes;
    try {
      (void)read_lattice_nrrd<double>(file("bad.nrrd"));
      ADD_FAILURE() << expected << ": no error";
    } catch (const NrrdError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  }
}

}  // namespace
}  // namespace boxgen::runtime
