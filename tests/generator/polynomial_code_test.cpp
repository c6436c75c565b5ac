// Emission strategies by name, and the shape of the code written for one orbit. The numbers in
// the code are checked where they are compiled and run: tests/emitted/emitted_accuracy_test.cpp.
#include "generator/polynomial_code.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "generator/error.h"
#include "tests/generator/analysis_fixture.h"

namespace boxgen {
namespace {

TEST(PolynomialCode, StrategiesByName) {
  EXPECT_EQ(parse_strategy("horner"), EmissionStrategy::Horner);
  EXPECT_EQ(parse_strategy("monomial"), EmissionStrategy::Monomial);
  EXPECT_STREQ(strategy_name(EmissionStrategy::Horner), "horner");
  EXPECT_STREQ(strategy_name(EmissionStrategy::Monomial), "monomial");
  EXPECT_EQ(parse_strategy("separable"), EmissionStrategy::Separable);
  EXPECT_EQ(parse_strategy("auto"), EmissionStrategy::Auto);
  EXPECT_THROW(parse_strategy("bernstein"), InputError);
}

TEST(PolynomialCode, OneFunctionPerOrbitInEachStrategy) {
  const Analysis& a = testing::analysis_of("zp");
  const ReferenceRegion& ref = a.structure.references[0];
  const auto horner = orbit_code(ref, 0, 2, 2, EmissionStrategy::Horner);
  const auto monomial = orbit_code(ref, 0, 2, 2, EmissionStrategy::Monomial);
  ASSERT_TRUE(horner && monomial);
  for (const OrbitCode* code : {&*horner, &*monomial}) {
    EXPECT_NE(code->text.find("orbit_0"), std::string::npos) << code->text;
    EXPECT_GT(code->value.total(), 0);
    EXPECT_GE(code->gradient.total(), code->value.total());
    EXPECT_GE(code->hessian.total(), code->gradient.total());
  }
  EXPECT_NE(horner->text, monomial->text);
  // The zp spline is not a tensor product: separable code does not apply, and auto picks the
  // cheaper of the others.
  EXPECT_FALSE(orbit_code(ref, 0, 2, 2, EmissionStrategy::Separable).has_value());
  const OrbitCode chosen = choose_orbit_code(ref, 0, 2, 2, EmissionStrategy::Auto);
  EXPECT_LE(chosen.gradient.total(),
            std::min(horner->gradient.total(), monomial->gradient.total()));
}

}  // namespace
}  // namespace boxgen
