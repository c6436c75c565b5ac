// The derivation on the true knot planes: the knot levels, the cell keys, exact point
// location of shifts, scale invariance, the symmetry-reduced checks against the full ones (and
// against broken forms, so they can fail).
#include <gtest/gtest.h>

#include "generator/error.h"
#include "generator/piece_checks.h"
#include "generator/recurrence.h"
#include "tests/generator/derivation_fixture.h"

namespace boxgen::generator {
namespace {

using fixture::derivation_of;

TEST(KnotPlanes, LevelsAreTheSubSumsAlongEachNormal) {
  // Directions (20,1), (1,20), (7,5), (-9,4). The normal of (20,1) is +-(1,-20); the dot products
  // of the four directions with (1,-20) are 0, -399, -93, -89 (by hand), whose sub-sums are
  // 0, -89, -93, -182, -399, -488, -492, -581: 8 knot lines where the integer levels would be 582.
  const IntColumns xi{{20, 1}, {1, 20}, {7, 5}, {-9, 4}};
  const KnotPlanes planes = knot_planes(xi, 2);
  ASSERT_EQ(planes.normals.size(), 4u);
  bool found = false;
  for (size_t i = 0; i < planes.normals.size(); ++i) {
    if (planes.normals[i] == IntVec{1, -20}) {
      EXPECT_EQ(planes.levels[i],
                (std::vector<std::int64_t>{-581, -492, -488, -399, -182, -93, -89, 0}));
      found = true;
    }
    if (planes.normals[i] == IntVec{-1, 20}) {
      EXPECT_EQ(planes.levels[i], (std::vector<std::int64_t>{0, 89, 93, 182, 399, 488, 492, 581}));
      found = true;
    }
  }
  EXPECT_TRUE(found);
}

TEST(KnotPlanes, IntervalKeyCountsTheLevelsStrictlyBelow) {
  const KnotPlanes planes{{{1, 0}}, {{0, 1, 2}}};
  EXPECT_EQ(interval_key(planes, {Rational(1) / 2, 0}), CellKey{1});
  EXPECT_EQ(interval_key(planes, {1, 0}), CellKey{1});  // on the level 1: the cell below
  EXPECT_EQ(interval_key(planes, {-5, 0}), CellKey{0});
  // Far outside: no 64-bit conversion (this once threw an internal error).
  EXPECT_EQ(interval_key(planes, {Rational(cln::expt_pos(Integer(10), 30)), 0}), CellKey{3});
  EXPECT_FALSE(off_knot_planes(planes, {2, 7}));
  EXPECT_TRUE(off_knot_planes(planes, {Rational(3) / 2, 7}));
}

TEST(KnotComplex, ShiftLocatorAgreesWithRationalLocation) {
  const PiecewiseForm& form = derivation_of("m7").form;
  int inside = 0;
  for (size_t c = 0; c < form.knots.cells().size(); c += 7) {
    const RatVec& p = form.knots.cells()[c].interior;
    const ShiftLocator locate(form.knots, p);
    for (const IntVec& j :
         {IntVec{0, 0, 0}, IntVec{1, 1, 1}, IntVec{-1, 1, -1}, IntVec{2, 0, 0}, IntVec{0, -2, 0}}) {
      RatVec q = p;
      for (int k = 0; k < 3; ++k) q[k] = q[k] - Rational(j[k]);
      EXPECT_EQ(locate.cell_at(j), form.knots.locate(q));
      inside += locate.cell_at(j) >= 0;
    }
  }
  EXPECT_GT(inside, 50);
}

// Long directions: the fine cells' interiors have large denominators (vertex means of crossings
// of normals such as (1,-20) and (20,-1)), and points with nu.p an integer (on or off a knot
// plane) take the cell below, as the rational location does.
TEST(KnotComplex, ShiftLocatorAgreesWithRationalLocationForLargeDenominators) {
  const BoxSplineSpec s = parse_spec("20,1; 1,20; 7,5; -9,4");
  const PiecewiseForm form = derive_piecewise(s, DerivationMethod::TruncatedPower);
  std::vector<RatVec> points;
  for (const IntVec& corner : {IntVec{0, 0}, IntVec{3, 5}})
    for (const auto& cell : split_cube(form.complex.normals(), corner))
      points.push_back(cell.interior);
  for (int a = 0; a < 6; ++a) points.push_back({Rational(a) / 3, Rational(a * a) / 2});
  int inside = 0, large = 0;
  for (const RatVec& p : points) {
    large += cln::denominator(p[0]) > 1000 || cln::denominator(p[1]) > 1000;
    const ShiftLocator locate(form.knots, p);
    for (std::int64_t x = -30; x <= 10; x += 3)
      for (std::int64_t y = -30; y <= 10; y += 2) {
        const RatVec q{p[0] - Rational(x), p[1] - Rational(y)};
        ASSERT_EQ(locate.cell_at({x, y}), form.knots.locate(q));
        inside += locate.cell_at({x, y}) >= 0;
      }
  }
  EXPECT_GT(large, 0);  // the case the locator once left to rational arithmetic
  EXPECT_GT(inside, 100);
}

// A scaled direction matrix on the correspondingly scaled lattice is the same spline: the knot
// complex, the pieces and the structure must not grow with the scale.
TEST(KnotComplex, ScaledMatrixOnScaledLatticeHasTheSameCells) {
  const Derivation& hat = derivation_of("hex3");
  DerivationOptions options;
  const Derivation scaled = derive(parse_spec("64,0; 0,64; 64,64", "64,0; 0,64"), options);
  EXPECT_EQ(scaled.form.knots.cells().size(), hat.form.knots.cells().size());
  EXPECT_EQ(scaled.pieces, hat.pieces);
  EXPECT_EQ(scaled.structure.regions.size(), hat.structure.regions.size());
  EXPECT_EQ(scaled.structure.references.size(), hat.structure.references.size());
  EXPECT_TRUE(scaled.checks.methods_agree);
}

// Long directions: values of the piecewise form against the independent recurrence.
TEST(KnotComplex, LongDirectionsAgreeWithTheRecurrence) {
  for (const char* spec :
       {"20,1; 1,20; 7,5; -9,4", "1,2,3; 3,1,2; 2,3,1; -1,2,3", "3,1; 1,3; 2,-5"}) {
    const BoxSplineSpec s = parse_spec(spec);
    const PiecewiseForm form = derive_piecewise(s, DerivationMethod::TruncatedPower);
    BoxSplineRecurrence recurrence(s.directions);
    int nonzero = 0;
    for (size_t c = 0; c < form.knots.cells().size(); ++c) {
      RatVec x = form.knots.cells()[c].interior;
      static const long primes[] = {1000003, 1000033, 1000037};
      for (size_t k = 0; k < x.size(); ++k)
        x[k] = x[k] + Rational(1) / primes[k];  // generic, nearby
      const Rational expected = recurrence.value(x);
      EXPECT_EQ(form.value_at(x), expected) << spec << " cell " << c;
      nonzero += !cln::zerop(expected);
    }
    EXPECT_GT(nonzero, 0) << spec;
    EXPECT_EQ(total_integral(form), 1) << spec;
  }
}

TEST(ReducedChecks, AgreeWithTheFullChecks) {
  for (const char* preset : {"m7", "cart7", "zp"}) {
    const Derivation& a = derivation_of(preset);
    const CellOrbits orbits = cell_orbits(a.form, a.structure.group);
    std::size_t cells = 0;
    for (int s : orbits.sizes) cells += static_cast<std::size_t>(s);
    EXPECT_EQ(cells, a.form.knots.cells().size()) << preset;  // the orbits partition the cells
    EXPECT_LT(orbits.representatives.size(), a.form.knots.cells().size()) << preset;
    EXPECT_EQ(total_integral(a.form, orbits), total_integral(a.form)) << preset;
    const int order = a.properties.approximation_order - 1;
    EXPECT_EQ(check_continuity(a.form, order, orbits.representatives).sharp,
              check_continuity(a.form, order).sharp);
    EXPECT_NO_THROW(check_partition_of_unity(a.form, a.structure, false)) << preset;
    EXPECT_NO_THROW(check_partition_of_unity(a.form, a.structure, true)) << preset;
  }
}

TEST(ReducedChecks, DetectABrokenPiece) {
  const Derivation& a = derivation_of("m7");
  PiecewiseForm broken = a.form;
  broken.polys[0] += Poly::constant(3, Rational(1) / 1000);  // cell 0 represents its orbit
  const CellOrbits orbits = cell_orbits(a.form, a.structure.group);
  EXPECT_NE(total_integral(broken, orbits), 1);
  EXPECT_THROW(check_continuity(broken, 3, orbits.representatives), InternalError);
  EXPECT_THROW(check_symmetry(broken, a.structure.group), InternalError);
}

TEST(ReducedChecks, PartitionOfUnityOnReferencesDetectsABrokenBasis) {
  SplineStructure s = derivation_of("m7").structure;
  s.references[0].basis[0] += Poly::constant(3, Rational(1) / 1000);
  EXPECT_THROW(check_partition_of_unity(derivation_of("m7").form, s, false), InternalError);
}

}  // namespace
}  // namespace boxgen::generator
