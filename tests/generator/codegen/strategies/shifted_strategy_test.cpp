// The shifted form: its origin chosen by count, its code in y = x - o (exactness:
// polynomial_code_test).
#include "generator/codegen/strategies/shifted_strategy.h"

#include <gtest/gtest.h>

#include <string>

#include "generator/codegen/strategies/horner_strategy.h"
#include "generator/codegen/targets/target_printer.h"
#include "tests/generator/derivation_fixture.h"

namespace boxgen::generator::strategies {
namespace {

// Orbit 0's code as the C++ printer writes it.
std::string cpp_text(const OrbitCode& code) { return CppPrinter().orbit_functions(code, 0); }

// The shifted form names its origin, a point of the reference region other than 0 that the
// generator chose by its own count: here M8's, the midpoint of two vertices, since the vertex at 0
// is the Horner form itself. Its code uses y = x - o and no other coordinates.
TEST(ShiftedStrategy, RecordsItsOriginAndWritesY) {
  const Derivation& a = fixture::derivation_of("m8");
  const ReferenceRegion& ref = a.structure.references[0];
  const auto shifted = shifted_code(ref, 0, 3, a.properties.degree);
  ASSERT_TRUE(shifted);
  EXPECT_EQ(shifted->form, "about (1,1,0)");
  EXPECT_NE(cpp_text(*shifted).find("origin o = (1,1,0)"), std::string::npos);
  EXPECT_NE(cpp_text(*shifted).find("const T y0 = x[0] - T(1);"), std::string::npos)
      << cpp_text(*shifted);
  EXPECT_NE(cpp_text(*shifted).find("const T y1 = x[1] - T(1);"), std::string::npos);
  EXPECT_EQ(cpp_text(*shifted).find("const T y2"), std::string::npos);  // o_2 = 0: x[2] itself
  // Horner about M8's corner costs more, so auto takes the shifted form (ties would keep Horner).
  const auto horner = horner_code(ref, 0, 3, a.properties.degree);
  EXPECT_LT(shifted->gradient.total(), horner->gradient.total());
  EXPECT_EQ(choose_orbit_code(ref, 0, 3, a.properties.degree, EmissionStrategy::Auto).strategy,
            EmissionStrategy::Shifted);
}

}  // namespace
}  // namespace boxgen::generator::strategies
