// The cost estimate (generator/cost_estimate): its knot-cell count is exact for the presets, and a
// refusal names the prediction and the option that raises the limit.
#include "generator/cost_estimate.h"

#include <gtest/gtest.h>

#include "generator/error.h"
#include "tests/generator/derivation_fixture.h"

namespace boxgen::generator {
namespace {

using fixture::derivation_of;

TEST(CostEstimate, CountsTheKnotCellsExactly) {
  for (const char* preset : {"m7", "fcc6", "zp"}) {
    const CostEstimate e = estimate_cost(parse_spec(preset));
    EXPECT_TRUE(e.cells_exact) << preset;
    EXPECT_EQ(e.knot_cells, derivation_of(preset).form.knots.cells().size()) << preset;
    EXPECT_EQ(e.fundamental_cells, derivation_of(preset).structure.cells.size()) << preset;
    EXPECT_GT(e.seconds, 0) << preset;
    EXPECT_GT(e.bytes, 1e6) << preset;
  }
}

TEST(CostEstimate, RefusalNamesThePredictionAndTheLimit) {
  CostEstimate e;
  e.seconds = 1234;
  e.bytes = 5e8;
  e.knot_cells = 99;
  try {
    refuse_if_too_costly(e, 100);
    FAIL() << "not refused";
  } catch (const InputError& err) {
    const std::string what = err.what();
    EXPECT_NE(what.find("1.23e+03 s"), std::string::npos) << what;
    EXPECT_NE(what.find("--max-seconds"), std::string::npos) << what;
  }
  EXPECT_NO_THROW(refuse_if_too_costly(e, 2000));
}

}  // namespace
}  // namespace boxgen::generator
