// Bernstein-Bezier code: where it applies and what it names (exactness: polynomial_code_test).
#include "generator/codegen/strategies/bernstein_strategy.h"

#include <gtest/gtest.h>

#include <string>

#include "generator/codegen/targets/target_printer.h"
#include "generator/error.h"
#include "tests/generator/derivation_fixture.h"

namespace boxgen::generator::strategies {
namespace {

// Orbit 0's code as the C++ printer writes it.
std::string cpp_text(const OrbitCode& code) { return CppPrinter().orbit_functions(code, 0); }

// Bernstein-Bezier code exists on simplices only: M7's tetrahedron and zp's triangle, not the
// cubes of M12; asking for it there is an input error naming the region.
TEST(BernsteinStrategy, OnSimplicesOnly) {
  const Derivation& m7 = fixture::derivation_of("m7");
  const auto bb = bernstein_code(m7.structure.references[0], 0, 3, 4);
  ASSERT_TRUE(bb);
  // Degree 4 in 3-D: 35 BB-coefficients, de Casteljau levels of 20, 10, 4 and 1 values; those
  // used once are written inline (the schedule, generator/codegen/ir/expr_schedule.h), so the names
  // that appear are the shared ones.
  EXPECT_NE(cpp_text(*bb).find("const T b1 ="), std::string::npos);
  EXPECT_NE(cpp_text(*bb).find("const T q1_1 ="), std::string::npos);
  // The last level is the value; level 3 also feeds the gradient, level 2 the Hessian.
  EXPECT_NE(cpp_text(*bb).find("const T q3_3 ="), std::string::npos);
  EXPECT_NE(cpp_text(*bb).find("const T q2_9 ="), std::string::npos);
  EXPECT_NE(cpp_text(*bb).find("const T value = "), std::string::npos);
  // Barycentric coordinates that are a coordinate itself are no temporaries (l3 = x[2]); l0 =
  // 1 - x[0] is kept as its negation x[0] - 1, subtracted where it is used.
  EXPECT_NE(cpp_text(*bb).find("const T l1 = x[0] - x[1];"), std::string::npos) << cpp_text(*bb);
  EXPECT_EQ(cpp_text(*bb).find("const T l3 ="), std::string::npos) << cpp_text(*bb);
  const Derivation& zp = fixture::derivation_of("zp");
  EXPECT_TRUE(bernstein_code(zp.structure.references[0], 0, 2, 2));
  const Derivation& m12 = fixture::derivation_of("m12");
  const ReferenceRegion& cube = m12.structure.references[0];
  EXPECT_FALSE(bernstein_code(cube, 0, 3, m12.properties.degree));
  try {
    choose_orbit_code(cube, 0, 3, m12.properties.degree, EmissionStrategy::Bernstein);
    ADD_FAILURE() << "bernstein on a cube";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not a simplex"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace boxgen::generator::strategies
