// BB-form: the coefficients reproduce every basis polynomial of every reference region exactly.
#include <gtest/gtest.h>

#include "generator/bbform.h"
#include "tests/generator/derivation_fixture.h"

namespace boxgen::generator {
namespace {

using fixture::derivation_of;

TEST(BBForm, RoundTripOnEveryReferenceRegion) {
  for (const char* preset : fixture::kAllPresets) {
    const Derivation& a = derivation_of(preset);
    for (const auto& ref : a.structure.references) {
      const RegionBBForm bb = region_bb_form(ref, a.properties.degree);
      for (const auto& s : bb.simplices)
        for (size_t k = 0; k < ref.basis.size(); ++k) {
          std::vector<Rational> c;
          for (const auto& row : s.weights) c.push_back(row[k]);
          EXPECT_EQ(bb_polynomial(c, s.vertices, a.properties.degree), ref.basis[k]) << preset;
        }
    }
  }
}

// The affine forms the Bernstein emission writes
// (generator/codegen/strategies/polynomial_code.cpp): exact, one per vertex, 1 at their vertex and
// 0 at the others, summing to 1 everywhere.
TEST(BBForm, BarycentricFormsAreExactAffineCoordinates) {
  int simplices = 0;
  for (const char* preset : fixture::kAllPresets) {
    const Derivation& a = derivation_of(preset);
    for (const auto& ref : a.structure.references) {
      const int n = static_cast<int>(ref.vertices[0].size());
      if (static_cast<int>(ref.vertices.size()) != n + 1) continue;
      ++simplices;
      const std::vector<RatVec> f = barycentric_forms(ref.vertices);
      ASSERT_EQ(f.size(), ref.vertices.size());
      auto at = [&](const RatVec& form, const RatVec& x) {
        Rational r = form[0];
        for (int j = 0; j < n; ++j) r = r + form[j + 1] * x[j];
        return r;
      };
      for (std::size_t i = 0; i < f.size(); ++i)
        for (std::size_t k = 0; k < ref.vertices.size(); ++k)
          EXPECT_EQ(at(f[i], ref.vertices[k]), Rational(i == k ? 1 : 0)) << preset;
      Rational sum = 0;
      for (const auto& form : f) sum = sum + at(form, ref.interior);
      EXPECT_EQ(sum, Rational(1)) << preset;
    }
  }
  EXPECT_GE(simplices, 5);  // M7, M8, cart7, fcc6 (two orbits), hex3, zp
}

TEST(BBForm, M7HasThePapersTable) {
  // Paper section 4.2 and its supplemental Table 1: 30 stencil points, 35 quartic coefficients.
  const Derivation& a = derivation_of("m7");
  const RegionBBForm bb = region_bb_form(a.structure.references.at(0), 4);
  EXPECT_FALSE(bb.triangulated);
  ASSERT_EQ(bb.simplices.size(), 1u);
  EXPECT_EQ(bb.stencil.size(), 30u);
  EXPECT_EQ(bb.simplices[0].indices.size(), 35u);
  // Each BB coefficient of the spline of V = 1 is 1 (partition of unity), so each row of the
  // table sums to 1.
  for (const auto& row : bb.simplices[0].weights) {
    Rational sum = 0;
    for (const auto& w : row) sum = sum + w;
    EXPECT_EQ(sum, 1);
  }
}

TEST(BBForm, CubesAreTriangulated) {
  const Derivation& a = derivation_of("m12");
  const RegionBBForm bb = region_bb_form(a.structure.references.at(0), 9);
  EXPECT_TRUE(bb.triangulated);
  EXPECT_GE(bb.simplices.size(), 5u);
}

TEST(BBForm, KnownCoefficientsOfASimplePolynomial) {
  // x on the unit triangle (0,0),(1,0),(0,1) in degree 2: c = values of x at the domain points
  // (b1/2): (b0,b1,b2) = (2,0,0):0 (1,1,0):1/2 (1,0,1):0 (0,2,0):1 (0,1,1):1/2 (0,0,2):0.
  const std::vector<RatVec> tri{{0, 0}, {1, 0}, {0, 1}};
  const auto c = bb_coefficients(Poly::affine({0, 1, 0}), tri, 2);
  const std::vector<Rational> expected{0, Rational(1) / 2, 0, 1, Rational(1) / 2, 0};
  EXPECT_EQ(c, expected);
}

}  // namespace
}  // namespace boxgen::generator
