// Quasi-interpolation: with the prefilters of Table 1 the spline reproduces every cubic exactly;
// without a prefilter it does not (docs/design.md §8). Checked as polynomial identities on the
// reference region: s(x) = sum_j (f * q)(j) M(x - j) = f(x).
#include <gtest/gtest.h>

#include <map>

#include "generator/prefilter.h"
#include "tests/generator/derivation_fixture.h"

namespace boxgen::generator {
namespace {

using fixture::derivation_of;

Rational monomial(const IntVec& p, const Exponent& e) {
  Rational v = 1;
  for (size_t i = 0; i < p.size(); ++i)
    for (int k = 0; k < e[i]; ++k) v = v * Rational(p[i]);
  return v;
}

// s(x) on the reference region for data V(j) = f(j) = j^e, prefiltered by q.
Poly reconstruct(const ReferenceRegion& ref, const Prefilter& q, const Exponent& e) {
  Poly s(3, 0);
  for (size_t k = 0; k < ref.stencil.size(); ++k) {
    Rational coefficient = 0;  // (f * q)(j) = sum_o q(o) f(j - o)
    for (const auto& w : q.weights) {
      IntVec jo = ref.stencil[k];
      for (int i = 0; i < 3; ++i) jo[i] -= w.offset[i];
      coefficient = coefficient + w.weight * monomial(jo, e);
    }
    s += ref.basis[k] * coefficient;
  }
  return s;
}

Prefilter identity_filter() {
  Prefilter q;
  q.weights.push_back({IntVec{0, 0, 0}, Rational(1)});
  return q;
}

TEST(PrefilterReproduction, CubicsAreReproducedWithQ1AndQ2) {
  for (const char* preset : {"m7", "m8", "m12"}) {
    const Derivation& a = derivation_of(preset);
    const auto& ref = a.structure.references.at(0);
    for (const auto& shells : {std::vector<int>{0, 1}, std::vector<int>{0, 1, 2}}) {
      const Prefilter q = derive_prefilter(a.spec, shells);
      for (const auto& e : monomial_exponents(3, 3)) {
        if (e[0] + e[1] + e[2] > 3) break;
        Poly f(3, 3);
        f.set_coefficient(e, 1);
        EXPECT_EQ(reconstruct(ref, q, e), f) << preset << " monomial " << e[0] << e[1] << e[2];
      }
    }
  }
}

TEST(PrefilterReproduction, CubicsAreReproducedWithTheFirInterpolationPrefilter) {
  // qfir:K keeps the approximation order (docs/design.md §18): the same identity, for K = 1..3.
  for (const char* preset : {"m7", "m8", "m12"}) {
    const Derivation& a = derivation_of(preset);
    const auto& ref = a.structure.references.at(0);
    const auto samples = lattice_samples(a.form);
    for (int k = 1; k <= 3; ++k) {
      const Prefilter q = derive_fir_prefilter(a.spec, k, samples);
      for (const auto& e : monomial_exponents(3, 3)) {
        if (e[0] + e[1] + e[2] > 3) break;
        Poly f(3, 3);
        f.set_coefficient(e, 1);
        EXPECT_EQ(reconstruct(ref, q, e), f)
            << preset << " qfir:" << k << " monomial " << e[0] << e[1] << e[2];
      }
    }
  }
}

TEST(PrefilterReproduction, CubicsAreReproducedByEveryMemberOfTheFamilyOfFreeParameters) {
  // q1opt and q2opt are members of prefilter_family with optimised double parameters taken
  // exactly: every member keeps the order, so the moment conditions hold exactly for them.
  for (const char* preset : {"m7", "m8", "m12"}) {
    const Derivation& a = derivation_of(preset);
    const auto& ref = a.structure.references.at(0);
    for (int which : {1, 2}) {
      const PrefilterFamily family =
          prefilter_family(a.spec, quasi_interpolation_shells(a.spec, which));
      RatVec t;
      for (size_t i = 0; i < family.basis.size(); ++i)  // an arbitrary double and a rational
        t.push_back(i % 2 ? Rational(-7) / 5 : exact_rational(0.12345678912345678));
      const Prefilter q = family_member(family, t);
      for (const auto& e : monomial_exponents(3, 3)) {
        if (e[0] + e[1] + e[2] > 3) break;
        Poly f(3, 3);
        f.set_coefficient(e, 1);
        EXPECT_EQ(reconstruct(ref, q, e), f)
            << preset << " q" << which << " family monomial " << e[0] << e[1] << e[2];
      }
    }
  }
}

TEST(PrefilterReproduction, TheFamilyHoldsQ1AndQ2AndSpansTheFreeWeights) {
  // The free parameters are weights of whole orbits: with them at their value in derive_prefilter
  // (zero where it set them to zero, the common weight otherwise) the member is that prefilter.
  for (const char* preset : {"m7", "m8", "m12"}) {
    const BoxSplineSpec spec = parse_spec(preset);
    for (int which : {1, 2}) {
      const auto shells = quasi_interpolation_shells(spec, which);
      const PrefilterFamily family = prefilter_family(spec, shells);
      const Prefilter q = derive_prefilter(spec, shells);
      std::map<IntVec, Rational> tap;
      for (const auto& w : q.weights) tap[w.offset] = w.weight;
      RatVec t;
      for (int orbit : family.free_orbits) t.push_back(tap.at(family.orbits[orbit].front()));
      const Prefilter member = family_member(family, t);
      ASSERT_EQ(member.weights.size(), q.weights.size()) << preset << " q" << which;
      for (size_t i = 0; i < q.weights.size(); ++i) {
        EXPECT_EQ(member.weights[i].offset, q.weights[i].offset);
        EXPECT_EQ(member.weights[i].weight, q.weights[i].weight) << preset << " q" << which;
      }
    }
  }
}

TEST(PrefilterReproduction, WithoutAPrefilterQuadraticsAreNotReproduced) {
  for (const char* preset : {"m7", "m8", "m12"}) {
    const auto& ref = derivation_of(preset).structure.references.at(0);
    // Linear data is reproduced by any box spline (symmetric, order >= 2)...
    Poly x(3, 1);
    x.set_coefficient({1, 0, 0}, 1);
    EXPECT_EQ(reconstruct(ref, identity_filter(), {1, 0, 0}), x) << preset;
    // ...but x^2 is smoothed: s = x^2 + Sigma_11, the variance of M^c along x.
    Poly x2(3, 2);
    x2.set_coefficient({2, 0, 0}, 1);
    EXPECT_NE(reconstruct(ref, identity_filter(), {2, 0, 0}), x2) << preset;
  }
}

}  // namespace
}  // namespace boxgen::generator
