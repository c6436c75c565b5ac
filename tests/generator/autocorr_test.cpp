#include "generator/autocorr.h"

#include <gtest/gtest.h>

#include "tests/generator/bspline_reference.h"
#include "tests/generator/paper_directions.h"

#include <map>

#include "generator/error.h"
#include "generator/symmetry.h"

namespace boxgen::generator {
namespace {

using fixture::concat;
using fixture::kXi1;
using fixture::kXi2;
using fixture::negated;

BoxSplineSpec m7() { return {"m7", "", concat({kXi1, kXi2}), Lattice::bcc()}; }
BoxSplineSpec m8() { return {"m8", "", concat({kXi1, kXi1}), Lattice::bcc()}; }
BoxSplineSpec m12() {
  return {"m12", "", concat({kXi2, kXi2, negated(kXi2), negated(kXi2)}), Lattice::bcc()};
}
BoxSplineSpec fcc6() {
  return {"fcc6",
          "",
          {{1, 1, 0}, {1, -1, 0}, {1, 0, 1}, {1, 0, -1}, {0, 1, 1}, {0, 1, -1}},
          Lattice::fcc()};
}
BoxSplineSpec cart7() {
  return {"cart7",
          "",
          {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}, {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}},
          Lattice::cartesian(3)};
}
BoxSplineSpec hex3() { return {"hex3", "", {{1, 0}, {0, 1}, {1, 1}}, Lattice::cartesian(2)}; }
BoxSplineSpec zp() { return {"zp", "", {{1, 0}, {0, 1}, {1, 1}, {-1, 1}}, Lattice::cartesian(2)}; }

Rational sum_of(const Autocorrelation& a) {
  Rational s = 0;
  for (const auto& x : a.samples) s = s + x.value;
  return s;
}

std::map<IntVec, Rational> as_map(const Autocorrelation& a) {
  std::map<IntVec, Rational> m;
  for (const auto& s : a.samples) m[s.point] = s.value;
  return m;
}

void expect_same(const Autocorrelation& a, const Autocorrelation& b, const std::string& name) {
  ASSERT_EQ(a.samples.size(), b.samples.size()) << name;
  for (std::size_t k = 0; k < a.samples.size(); ++k) {
    EXPECT_EQ(a.samples[k].point, b.samples[k].point) << name;
    EXPECT_EQ(a.samples[k].value, b.samples[k].value) << name << " at sample " << k;
  }
  EXPECT_EQ(a.integral_squared, b.integral_squared) << name;
}

// Invariance is imposed by the orbit-reduced refinement, so check it on results that do not
// assume it: the continuity limits and the refinement solved on every lattice point.
void expect_invariant(const BoxSplineSpec& spec, const Autocorrelation& a) {
  const auto values = as_map(a);
  const auto group = symmetry_group(spec);
  EXPECT_GT(group.size(), 1u);
  for (const auto& g : group)
    for (const auto& [p, v] : values) {
      auto it = values.find(g.apply(p));
      ASSERT_NE(it, values.end()) << spec.name;
      EXPECT_EQ(it->second, v) << spec.name;
    }
}

TEST(Autocorr, RefinementAndContinuityAgreeOnM7) {
  const auto r = autocorrelation_refinement(m7());
  const auto c = autocorrelation_continuity(m7());
  EXPECT_GT(r.samples.size(), 100u);
  expect_same(r, c, "m7");
  expect_invariant(m7(), c);
}

TEST(Autocorr, RefinementAndContinuityAgreeOnM8) {
  const auto r = autocorrelation_refinement(m8());
  const auto c = autocorrelation_continuity(m8());
  EXPECT_GT(r.samples.size(), 100u);
  expect_same(r, c, "m8");
  expect_invariant(m8(), c);
}

TEST(Autocorr, RefinementAndContinuityAgreeOnFcc6AndIn2D) {
  for (const auto& spec : {fcc6(), hex3(), zp()})
    expect_same(autocorrelation_refinement(spec), autocorrelation_continuity(spec), spec.name);
}

TEST(Autocorr, ContinuityRefusesSplinesTooLargeForIt) {
  EXPECT_THROW(autocorrelation_continuity(m12()), InputError);  // 5^6 sub-multisets
}

// The known value quoted in docs/design.md §9.
TEST(Autocorr, M7IntegralOfSquareIsTheKnownValue) {
  EXPECT_EQ(autocorrelation_refinement(m7()).integral_squared, Rational(39559) / 1064448);
}

TEST(Autocorr, SamplesSumToInverseLatticeDeterminant) {
  for (const auto& spec : {m7(), m8(), m12(), fcc6(), cart7(), hex3(), zp()}) {
    const auto a = autocorrelation_refinement(spec);
    EXPECT_EQ(sum_of(a), Rational(1) / rational_from(spec.lattice.det_abs())) << spec.name;
  }
}

// The Courant hat h is linear on six triangles of area 1/2; a(j) = ∫ h(x) h(x - j) dx. With the
// simplex formula ∫_T l_i l_j = |T|/12 (i != j) and ∫_T l_i^2 = |T|/6: a(0) = 6 * (1/2)/6 = 1/2;
// each of the six hexagon vertices shares two triangles with the centre: 2 * (1/2)/12 = 1/12.
TEST(Autocorr, CourantElementByTheSimplexFormula) {
  const auto a = autocorrelation_refinement(hex3());
  std::map<IntVec, Rational> expected{{{0, 0}, Rational(1) / 2}};
  for (const IntVec& j :
       {IntVec{1, 0}, IntVec{0, 1}, IntVec{1, 1}, IntVec{-1, 0}, IntVec{0, -1}, IntVec{-1, -1}})
    expected[j] = Rational(1) / 12;
  EXPECT_EQ(as_map(a), expected);
}

using fixture::cardinal_bspline;
using fixture::power;

// Doubled m12 is, per coordinate, the 1-D box spline of eight columns +-2: centred, that is
// B_8(x/2 + 4)/2 (scaling by 2, centring the order-8 B-spline on [0, 8]).
TEST(Autocorr, M12IsProductOfOneDimensionalDoubledBsplines) {
  const auto a = as_map(autocorrelation_refinement(m12()));
  const Lattice bcc = Lattice::bcc();
  std::size_t nonzero = 0;
  for (const auto& j : bcc.points_in_box({-9, -9, -9}, {9, 9, 9})) {
    Rational expected = 1;
    for (auto c : j)
      expected = expected * cardinal_bspline(8, Rational(rational_from(c)) / 2 + 4) / 2;
    auto it = a.find(j);
    EXPECT_EQ(it == a.end() ? Rational(0) : it->second, expected);
    nonzero += !cln::zerop(expected);
  }
  EXPECT_EQ(nonzero, a.size());
}

// The exact solve on every lattice point assumes no symmetry, so its invariance is a real check
// (m7 and m8 are checked on their continuity limits above).
TEST(Autocorr, FullRefinementIsInvariantAndMatchesOrbitReduction) {
  for (const auto& spec : {fcc6(), hex3(), zp()}) {
    const auto full = autocorrelation_refinement(spec, {.reduce_by_symmetry = false});
    expect_invariant(spec, full);
    expect_same(full, autocorrelation_refinement(spec), spec.name);
  }
}

TEST(Autocorr, RejectsDirectionsOutsideTheLattice) {
  const BoxSplineSpec bad{"bad", "", {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}}, Lattice::bcc()};
  EXPECT_THROW(autocorrelation_refinement(bad), InputError);
  EXPECT_THROW(autocorrelation_continuity(bad), InputError);
}

TEST(Autocorr, DoubledSpecRepeatsTheColumns) {
  const auto d = doubled_spec(hex3());
  EXPECT_EQ(d.directions, (IntColumns{{1, 0}, {0, 1}, {1, 1}, {1, 0}, {0, 1}, {1, 1}}));
  EXPECT_EQ(d.lattice.det_abs(), 1);
}

}  // namespace
}  // namespace boxgen::generator
