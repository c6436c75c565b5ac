// Sums over one common denominator (generator/poly_sum.h) against the rational sums of Poly,
// on the stencils of reference regions of several direction matrices, and the
// partition-of-unity check built on them (it must still fail on a broken basis).
#include "generator/poly_sum.h"

#include <gtest/gtest.h>

#include <optional>
#include <set>

#include "generator/error.h"
#include "tests/generator/derivation_fixture.h"

namespace boxgen::generator {
namespace {

using fixture::derivation_of;

TEST(PolySum, ScaledTermsOfDifferentDenominatorsSumExactly) {
  Poly a(2, 1), b(2, 2);
  a.set_coefficient({1, 0, 0}, Rational(1) / 6);
  a.set_coefficient({0, 0, 0}, Rational(3) / 4);
  b.set_coefficient({1, 1, 0}, Rational(-5) / 9);
  b.set_coefficient({1, 0, 0}, Rational(-1) / 6);
  const ScaledPoly sa = scaled(a), sb = scaled(b), zero = scaled(Poly(2, 0));
  EXPECT_EQ(sa.denominator, 12);
  EXPECT_EQ(sb.denominator, 18);
  EXPECT_TRUE(zero.is_zero());
  EXPECT_FALSE(sa.is_zero());
  EXPECT_EQ(sum_scaled(2, {&sa, &sb}), a + b);  // the x terms cancel
  EXPECT_EQ(sum_scaled(2, {&sa, &sb, &sa, &zero}), a + b + a);
  EXPECT_TRUE(sum_scaled(2, {}).is_zero());
}

TEST(PolySum, CommonDenominatorIsTheLcmOfTheCoefficientDenominators) {
  Poly a(2, 1), b(2, 2);
  a.set_coefficient({1, 0, 0}, Rational(1) / 6);
  a.set_coefficient({0, 0, 0}, Rational(3) / 4);
  b.set_coefficient({1, 1, 0}, Rational(-5) / 9);
  EXPECT_EQ(common_denominator({&a}), 12);
  EXPECT_EQ(common_denominator({&a, &b}), 36);
  EXPECT_EQ(common_denominator({}), 1);
  EXPECT_EQ(scaled_numerators(a, 12), (std::vector<Integer>{9, 2, 0}));
  EXPECT_THROW(scaled_numerators(a, 6), InternalError);  // 6 * 3/4 is not an integer
}

// The exact sum over one denominator equals the sum of the rational polynomials, term by term
// in the order the basis lists them, for each reference region's stencil.
TEST(PolySum, StencilSumsEqualTheRationalSums) {
  for (const char* preset : {"m7", "m8", "hex3", "zp", "cart7"}) {
    const SplineStructure& s = derivation_of(preset).structure;
    for (const auto& ref : s.references) {
      std::vector<const Poly*> terms;
      std::vector<int> all, odd;
      Poly rational(static_cast<int>(s.centre.size()), 0), rational_odd = rational;
      for (size_t k = 0; k < ref.basis.size(); ++k) {
        terms.push_back(&ref.basis[k]);
        all.push_back(static_cast<int>(k));
        rational += ref.basis[k];
        if (k % 2 == 1) {
          odd.push_back(static_cast<int>(k));
          rational_odd += ref.basis[k];
        }
      }
      const CommonDenominatorTerms exact(static_cast<int>(s.centre.size()), terms);
      // Each term over its own denominator (the truncated power's sums), summed the same.
      std::vector<ScaledPoly> own;
      for (const Poly* t : terms) own.push_back(scaled(*t));
      std::vector<const ScaledPoly*> own_odd, own_all;
      for (size_t k = 0; k < own.size(); ++k) {
        own_all.push_back(&own[k]);
        if (k % 2 == 1) own_odd.push_back(&own[k]);
      }
      EXPECT_EQ(sum_scaled(static_cast<int>(s.centre.size()), own_all), rational) << preset;
      EXPECT_EQ(sum_scaled(static_cast<int>(s.centre.size()), own_odd), rational_odd) << preset;
      EXPECT_EQ(exact.sum(all), rational) << preset;
      EXPECT_EQ(exact.sum(odd), rational_odd) << preset;
      EXPECT_TRUE(exact.sum_is_constant(all, 1)) << preset;  // partition of unity
      EXPECT_FALSE(exact.sum_is_constant(odd, 1)) << preset;
      EXPECT_FALSE(exact.sum_is_constant(all, Rational(1) / 2)) << preset;
      // A repeated term counts twice.
      std::vector<int> twice = all;
      twice.push_back(0);
      EXPECT_EQ(exact.sum(twice), rational + ref.basis[0]) << preset;
    }
  }
}

// Long directions: large denominators, and many regions sharing terms.
TEST(PolySum, LongDirectionsStencilSumsEqualTheRationalSums) {
  DerivationOptions options;
  options.verify = false;
  const Derivation a = derive(parse_spec("3,1; 1,3; 2,-5"), options);
  std::vector<const Poly*> terms;
  for (const auto& ref : a.structure.references)
    for (const auto& b : ref.basis) terms.push_back(&b);
  const CommonDenominatorTerms exact(2, terms);
  int first = 0;
  for (const auto& ref : a.structure.references) {
    std::vector<int> indices;
    Poly rational(2, 0);
    for (const auto& b : ref.basis) {
      indices.push_back(first++);
      rational += b;
    }
    EXPECT_EQ(exact.sum(indices), rational);
    EXPECT_EQ(rational, Poly::constant(2, 1));
  }
  EXPECT_NO_THROW(check_partition_of_unity(a.form, a.structure, false));
  EXPECT_NO_THROW(check_partition_of_unity(a.form, a.structure, true));
}

// The reduced check takes each distinct (knot cell, j) term once: a basis polynomial broken in a
// later region (a term seen before) must still make it fail.
TEST(PolySum, PartitionOfUnityDetectsABrokenRepeatedTerm) {
  const Derivation a = derive(parse_spec("3,1; 1,3; 2,-5"), DerivationOptions{});
  const auto& refs = a.structure.references;
  std::set<std::pair<int, IntVec>> seen;
  std::optional<std::pair<size_t, size_t>> repeated;  // (reference, stencil index)
  for (size_t r = 0; r < refs.size() && !repeated; ++r)
    for (size_t k = 0; k < refs[r].stencil.size() && !repeated; ++k)
      if (!seen.emplace(refs[r].stencil_knot_cells[k], refs[r].stencil[k]).second)
        repeated = std::make_pair(r, k);
  ASSERT_TRUE(repeated.has_value());
  SplineStructure s = a.structure;
  s.references[repeated->first].basis[repeated->second] += Poly::constant(2, Rational(1) / 1000);
  EXPECT_THROW(check_partition_of_unity(a.form, s, false), InternalError);
  SplineStructure dropped = a.structure;
  auto& ref = dropped.references[repeated->first];
  ref.basis.erase(ref.basis.begin() + static_cast<std::ptrdiff_t>(repeated->second));
  ref.stencil.erase(ref.stencil.begin() + static_cast<std::ptrdiff_t>(repeated->second));
  ref.stencil_knot_cells.erase(ref.stencil_knot_cells.begin() +
                               static_cast<std::ptrdiff_t>(repeated->second));
  EXPECT_THROW(check_partition_of_unity(a.form, dropped, false), InternalError);
}

}  // namespace
}  // namespace boxgen::generator
