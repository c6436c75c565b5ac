// The monomial form: one coefficient per monomial that some stencil polynomial holds (exactness of
// the graph: polynomial_code_test).
#include "generator/codegen/strategies/monomial_strategy.h"

#include <gtest/gtest.h>

#include <string>

#include "tests/generator/derivation_fixture.h"

namespace boxgen::generator::strategies {
namespace {

std::string comment_field(const OrbitCode& code, const std::string& name) {
  for (const auto& [key, value] : code.comment.args)
    if (key == name) return value;
  return "";
}

// The comment counts the monomials with a non-zero coefficient in some basis polynomial, counted
// here from the basis itself; the graph loads every stencil value.
TEST(MonomialStrategy, OneCoefficientPerMonomialInTheBasis) {
  for (const char* preset : {"zp", "m7"}) {
    const Derivation& a = fixture::derivation_of(preset);
    const int n = a.spec.dimension();
    const ReferenceRegion& ref = a.structure.references[0];
    std::size_t used = 0;
    for (std::size_t m = 0; m < monomial_count(n, a.properties.degree); ++m) {
      bool nonzero = false;
      for (const Poly& p : ref.basis)
        nonzero = nonzero || (m < p.coefficients().size() && !cln::zerop(p.coefficients()[m]));
      used += nonzero ? 1 : 0;
    }
    const auto code = monomial_code(ref, 0, n, a.properties.degree);
    ASSERT_TRUE(code) << preset;
    EXPECT_EQ(code->strategy, EmissionStrategy::Monomial);
    EXPECT_EQ(comment_field(*code, "monomials"), std::to_string(used)) << preset;
    EXPECT_EQ(comment_field(*code, "stencil"), std::to_string(ref.stencil.size())) << preset;
    EXPECT_EQ(code->value.loads, static_cast<long>(ref.stencil.size())) << preset;
  }
}

}  // namespace
}  // namespace boxgen::generator::strategies
