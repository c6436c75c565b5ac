// Emission strategies by name, and the shape of the code written for one orbit. The numbers in
// the code are checked where they are compiled and run: tests/emitted/emitted_accuracy_test.cpp.
#include "generator/polynomial_code.h"

#include <gtest/gtest.h>

#include "generator/error.h"
#include "tests/generator/analysis_fixture.h"

namespace boxgen {
namespace {

TEST(PolynomialCode, StrategiesByName) {
  EXPECT_EQ(parse_strategy("horner"), EmissionStrategy::Horner);
  EXPECT_EQ(parse_strategy("monomial"), EmissionStrategy::Monomial);
  EXPECT_STREQ(strategy_name(EmissionStrategy::Horner), "horner");
  EXPECT_STREQ(strategy_name(EmissionStrategy::Monomial), "monomial");
  EXPECT_THROW(parse_strategy("bernstein"), InputError);
}

TEST(PolynomialCode, OneFunctionPerOrbitInEachStrategy) {
  const Analysis& a = testing::analysis_of("zp");
  const ReferenceRegion& ref = a.structure.references[0];
  const std::string horner = orbit_function(ref, 0, 2, 2, EmissionStrategy::Horner);
  const std::string monomial = orbit_function(ref, 0, 2, 2, EmissionStrategy::Monomial);
  for (const std::string& code : {horner, monomial}) {
    EXPECT_NE(code.find("orbit_0"), std::string::npos) << code;
    EXPECT_NE(code.find("gradient"), std::string::npos) << code;
  }
  EXPECT_NE(horner, monomial);
}

}  // namespace
}  // namespace boxgen
