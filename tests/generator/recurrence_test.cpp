#include "generator/recurrence.h"

#include <gtest/gtest.h>

#include "tests/generator/bspline_reference.h"
#include "tests/generator/paper_directions.h"

#include <algorithm>

#include "generator/error.h"
#include "generator/lattice.h"

namespace boxgen::generator {
namespace {

using fixture::concat;
using fixture::kXi1;
using fixture::kXi2;
using fixture::negated;

const IntColumns kM7 = concat({kXi1, kXi2});
const IntColumns kM8 = concat({kXi1, kXi1});
const IntColumns kM12 = concat({kXi2, kXi2, negated(kXi2), negated(kXi2)});
const IntColumns kFcc6 = {{1, 1, 0}, {1, -1, 0}, {1, 0, 1}, {1, 0, -1}, {0, 1, 1}, {0, 1, -1}};
const IntColumns kCart7 = {{1, 0, 0},  {0, 1, 0},  {0, 0, 1}, {1, 1, 1},
                           {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}};
const IntColumns kHex3 = {{1, 0}, {0, 1}, {1, 1}};
const IntColumns kZp = {{1, 0}, {0, 1}, {1, 1}, {-1, 1}};

// Points with distinct large prime denominators per coordinate are off every integer knot plane
// nu.x = c with small nu. `lo`/`width` place them in a box.
class GenericPoints {
 public:
  explicit GenericPoints(std::uint64_t seed) : state_(seed) {}
  RatVec next(int n, std::int64_t lo, std::int64_t width) {
    static const std::int64_t primes[3] = {1000003, 1000033, 1000037};
    RatVec x;
    for (int i = 0; i < n; ++i) {
      std::int64_t num;
      do num = static_cast<std::int64_t>(step() % static_cast<std::uint64_t>(width * primes[i]));
      while (num % primes[i] == 0);
      x.push_back(rational_from(lo) + rational_from(num) / rational_from(primes[i]));
    }
    return x;
  }

 private:
  std::uint64_t step() {
    state_ = state_ * 6364136223846793005ULL + 1442695040888963407ULL;
    return state_ >> 11;
  }
  std::uint64_t state_;
};

using fixture::cardinal_bspline;
using fixture::power;

TEST(Recurrence, ParallelepipedBaseCase) {
  const IntColumns xi = {{1, 1, 1}, {1, -1, -1}, {0, 2, 0}};
  ASSERT_EQ(std::llabs(det(xi)), 4);
  GenericPoints gen(7);
  for (int k = 0; k < 40; ++k) {
    // t in (-1/2, 3/2)^3 with prime denominators; x = Xi t is then generic for this Xi.
    RatVec t = gen.next(3, -1, 4);
    for (auto& v : t) v = v / 2;
    RatVec x(3, 0);
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) x[i] = x[i] + rational_from(xi[j][i]) * t[j];
    const bool inside =
        std::all_of(t.begin(), t.end(), [](const Rational& v) { return v > 0 && v < 1; });
    EXPECT_EQ(box_spline_recurrence(xi, x), inside ? Rational(1) / 4 : Rational(0)) << k;
  }
}

// The three-direction (Courant) element is the piecewise-linear hat on the hexagon
// (0,0),(1,0),(2,1),(2,2),(1,2),(0,1) with height 1 at (1,1) (volume = area 3 * height / 3 = 1).
// A pyramid over a convex base is the minimum of its face planes, each 0 on one hexagon edge and
// 1 at the apex: hat = max(0, min(x, y, 1-x+y, 1+x-y, 2-x, 2-y)).
TEST(Recurrence, CourantElementMatchesClosedForm) {
  GenericPoints gen(11);
  int inside = 0;
  for (int k = 0; k < 200; ++k) {
    const RatVec x = gen.next(2, -1, 4);
    Rational hat = std::min({x[0], x[1], 1 - x[0] + x[1], 1 + x[0] - x[1], 2 - x[0], 2 - x[1]});
    if (hat < 0)
      hat = 0;
    else
      ++inside;
    EXPECT_EQ(box_spline_recurrence(kHex3, x), hat) << k;
  }
  EXPECT_GT(inside, 30);  // the sample hits the support, not only the zero region
  // On the triangle 0 < y < x < 1 the closed form is y.
  const RatVec p = {Rational(700001) / 1000003, Rational(300007) / 1000033};
  EXPECT_EQ(box_spline_recurrence(kHex3, p), p[1]);
}

TEST(Recurrence, OneDimensionalBoxSplineIsTheCardinalBspline) {
  GenericPoints gen(3);
  for (int k = 0; k < 50; ++k) {
    const RatVec x = gen.next(1, -1, 6);
    EXPECT_EQ(box_spline_recurrence({{1}, {1}, {1}, {1}}, x), cardinal_bspline(4, x[0])) << k;
  }
}

TEST(Recurrence, TricubicIsProductOfCubicBsplines) {
  const IntColumns eye = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const IntColumns xi = concat({eye, eye, eye, eye});
  GenericPoints gen(13);
  for (int k = 0; k < 100; ++k) {
    const RatVec x = gen.next(3, -1, 6);
    EXPECT_EQ(box_spline_recurrence(xi, x),
              cardinal_bspline(4, x[0]) * cardinal_bspline(4, x[1]) * cardinal_bspline(4, x[2]))
        << k;
  }
}

// m12 is a tensor product of the 1-D box spline with columns (2, 2, -2, -2). Flipping a column
// shifts: M_{..,-c}(x) = M_{..,c}(x + c); scaling: M_{[2,2,2,2]}(y) = B_4(y/2)/2.
Rational m12_factor(const Rational& x) { return cardinal_bspline(4, (x + 4) / 2) / 2; }

TEST(Recurrence, M12IsProductOfOneDimensionalBsplines) {
  GenericPoints gen(17);
  for (int k = 0; k < 60; ++k) {
    const RatVec x = gen.next(3, -5, 10);
    EXPECT_EQ(box_spline_recurrence(kM12, x),
              m12_factor(x[0]) * m12_factor(x[1]) * m12_factor(x[2]))
        << k;
  }
}

TEST(Recurrence, CentredM12IsCentredProduct) {
  GenericPoints gen(19);
  for (int k = 0; k < 20; ++k) {
    const RatVec x = gen.next(3, -5, 10);
    Rational expected = 1;
    for (const auto& c : x) expected = expected * cardinal_bspline(4, c / 2 + 2) / 2;
    EXPECT_EQ(box_spline_centred_recurrence(kM12, x), expected) << k;
  }
}

// sum_{j in L} M_Xi(x - j) = 1/|det G| (docs/design.md §1); all shifts share one memo.
Rational sum_of_shifts(const IntColumns& xi, const Lattice& lattice, const RatVec& x) {
  const int n = lattice.dimension();
  IntVec lo(n, 0), hi(n, 0);
  for (const auto& c : xi)
    for (int i = 0; i < n; ++i) (c[i] < 0 ? lo[i] : hi[i]) += c[i];
  // x - j in [lo, hi]  <=>  j in [x - hi, x - lo]
  IntVec jlo(n), jhi(n);
  for (int i = 0; i < n; ++i) {
    jlo[i] = floor_to_int64(x[i] - rational_from(hi[i]));
    jhi[i] = floor_to_int64(x[i] - rational_from(lo[i])) + 1;
  }
  BoxSplineRecurrence rec(xi);
  rec.set_base(x);
  Rational sum = 0;
  int nonzero = 0;
  for (const auto& j : lattice.points_in_box(jlo, jhi)) {
    IntVec minus_j = j;
    for (auto& v : minus_j) v = -v;
    const Rational v = rec.at_shift(minus_j);
    if (!cln::zerop(v)) ++nonzero;
    sum = sum + v;
  }
  EXPECT_GT(nonzero, 1);
  return sum;
}

TEST(Recurrence, PartitionOfUnityOnTheLattice) {
  struct Case {
    const char* name;
    IntColumns xi;
    Lattice lattice;
  };
  const Case cases[] = {{"m7", kM7, Lattice::bcc()},
                        {"m8", kM8, Lattice::bcc()},
                        {"fcc6", kFcc6, Lattice::fcc()},
                        {"cart7", kCart7, Lattice::cartesian(3)},
                        {"hex3", kHex3, Lattice::cartesian(2)},
                        {"zp", kZp, Lattice::cartesian(2)}};
  GenericPoints gen(23);
  for (const auto& c : cases)
    for (int k = 0; k < 5; ++k) {
      const RatVec x = gen.next(c.lattice.dimension(), -3, 6);
      EXPECT_EQ(sum_of_shifts(c.xi, c.lattice, x), Rational(1) / rational_from(c.lattice.det_abs()))
          << c.name;
    }
}

TEST(Recurrence, CentredSplineIsEven) {
  GenericPoints gen(29);
  for (const IntColumns& xi : {kM7, kM8, kFcc6, kCart7, kHex3, kZp}) {
    const int n = static_cast<int>(xi[0].size());
    int nonzero = 0;
    for (int k = 0; k < 10; ++k) {
      RatVec x = gen.next(n, -2, 4);
      if (k % 2 == 0)
        for (auto& v : x) v = v / 4;  // near the centre: inside every support here
      RatVec minus = x;
      for (auto& v : minus) v = -v;
      const Rational a = box_spline_centred_recurrence(xi, x);
      EXPECT_EQ(a, box_spline_centred_recurrence(xi, minus));
      nonzero += !cln::zerop(a);
    }
    EXPECT_GE(nonzero, 5);
  }
}

TEST(Recurrence, SharedMemoMatchesFreshEvaluation) {
  GenericPoints gen(31);
  const RatVec x = gen.next(3, -1, 2);
  BoxSplineRecurrence rec(kM7);
  rec.set_base(x);
  for (const IntVec& j :
       {IntVec{0, 0, 0}, IntVec{1, 1, 1}, IntVec{-2, 0, 0}, IntVec{1, -1, 1}, IntVec{9, 9, 9}}) {
    RatVec y = x;
    for (int i = 0; i < 3; ++i) y[i] = y[i] + rational_from(j[i]);
    EXPECT_EQ(rec.at_shift(j), box_spline_recurrence(kM7, y));
  }
}

TEST(Recurrence, RejectsNonGenericPointsAndBadMatrices) {
  EXPECT_FALSE(
      is_generic_point(kM7, {Rational(1) / 3, Rational(1) / 3, Rational(1) / 3}));  // on x2 = x3
  EXPECT_FALSE(is_generic_point(kM7, {0, Rational(1) / 3, Rational(1) / 5}));       // on x1 = 0
  EXPECT_TRUE(is_generic_point(kM7, {Rational(1) / 7, Rational(1) / 11, Rational(1) / 13}));
  EXPECT_THROW(box_spline_recurrence(kM7, {0, Rational(1) / 3, Rational(1) / 5}), InputError);
  EXPECT_THROW(box_spline_recurrence({{1, 0, 0}, {0, 0, 0}, {0, 0, 1}}, {Rational(1) / 7, 0, 0}),
               InputError);
  EXPECT_THROW(box_spline_recurrence({{1, 0, 0}, {2, 0, 0}, {0, 0, 1}}, {Rational(1) / 7, 0, 0}),
               InputError);
  EXPECT_THROW(box_spline_recurrence(kM7, {Rational(1) / 7, Rational(1) / 11}), InputError);
}

TEST(Recurrence, KnotPlaneNormals) {
  EXPECT_EQ(knot_plane_normals(kHex3), (std::vector<IntVec>{{0, 1}, {1, -1}, {1, 0}}));
  // m12: only the coordinate planes.
  EXPECT_EQ(knot_plane_normals(kM12), (std::vector<IntVec>{{0, 0, 1}, {0, 1, 0}, {1, 0, 0}}));
}

}  // namespace
}  // namespace boxgen::generator
