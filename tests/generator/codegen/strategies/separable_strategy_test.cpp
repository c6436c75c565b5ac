// The separable form: tensor products only, one contraction per grid (exactness of the graph:
// polynomial_code_test).
#include "generator/codegen/strategies/separable_strategy.h"

#include <gtest/gtest.h>

#include <string>

#include "generator/codegen/targets/target_printer.h"
#include "tests/generator/derivation_fixture.h"

namespace boxgen::generator::strategies {
namespace {

// Tricubic's 64 stencil values are one 4x4x4 grid: 1-D weights w<grid>_<axis>_<position>_<order>
// and the contraction, cheaper than Horner in 3-D; zp's box spline is no tensor product.
TEST(SeparableStrategy, TensorGridsOnly) {
  const Derivation& tricubic = fixture::derivation_of("tricubic");
  const ReferenceRegion& cube = tricubic.structure.references[0];
  const auto code = separable_code(cube, 0, 3, tricubic.properties.degree);
  ASSERT_TRUE(code);
  const std::string comment = orbit_comment(*code);
  EXPECT_NE(comment.find("its 64 stencil values form full grids (4x4x4)"), std::string::npos)
      << comment;
  EXPECT_NE(CppPrinter().orbit_functions(*code, 0).find("w0_2_3_1"), std::string::npos);
  const Derivation& zp = fixture::derivation_of("zp");
  EXPECT_FALSE(separable_code(zp.structure.references[0], 0, 2, zp.properties.degree));
}

}  // namespace
}  // namespace boxgen::generator::strategies
