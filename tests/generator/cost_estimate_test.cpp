// The cost estimate (generator/cost_estimate): its knot-cell count is exact for the presets, and a
// refusal names the prediction and the option that raises the limit.
#include "generator/cost_estimate.h"

#include <gtest/gtest.h>

#include <vector>

#include "generator/derivation.h"
#include "generator/error.h"
#include "support/available_memory.h"
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

// Tensor-product B-splines: the first k columns e1 (p times) and e2 (q times) have p * q unit
// squares as cells, so every level of the directional integration is counted by hand.
TEST(CostEstimate, CountsTheIntegrationLevelsOfATensorProduct) {
  // basis_first: e1, e2, then e1, e1, e2, e2 -> prefixes (1,1), (2,1), (3,1), (3,2).
  const BoxSplineSpec spec = parse_spec("1,0; 0,1; 1,0; 1,0; 0,1; 0,1", "cartesian");
  bool exact = false;
  EXPECT_EQ(integration_level_cells(spec, &exact), (std::vector<std::size_t>{1, 2, 3, 6}));
  EXPECT_TRUE(exact);
  // The box e1 x3, e2 x3, e3 x2: levels (1,1,1), (2,1,1), (3,1,1), (3,2,1), (3,3,1).
  const BoxSplineSpec box = parse_spec("1,0,0; 0,1,0; 0,0,1; 1,0,0; 1,0,0; 0,1,0; 0,1,0; 0,0,1");
  EXPECT_EQ(integration_level_cells(box), (std::vector<std::size_t>{1, 2, 3, 6, 9}));
  // The whole estimate carries the same counts.
  EXPECT_EQ(estimate_cost(spec).level_cells, (std::vector<std::size_t>{1, 2, 3, 6}));
}

// Counted by hand from Poly::along_direction and LevelIntegrator::jump: degree 1 in 2-D has the
// monomials 1, x, y; along (1,0) they expand into 1 + 2 + 1 terms, along (1,1) into 1 + 2 + 2;
// the jump's Horner runs over 3 terms G_e, each a product by an affine form (3 x 6 coefficients
// of degree <= 2) and two sums of 3 coefficients: 3 x (18 + 6) = 72.
TEST(CostEstimate, IntegrationWorkFollowsTheLoops) {
  EXPECT_EQ(integration_work(2, 1, {1, 0}), 4 + 72);
  EXPECT_EQ(integration_work(2, 1, {1, 1}), 5 + 72);
  // Degree 0: one monomial; Horner over 2 terms of 4 x 4 + 2 x 1 in 3-D.
  EXPECT_EQ(integration_work(3, 0, {1, 1, 1}), 1 + 2 * (4 * 4 + 2));
}

TEST(CostEstimate, RefusesBeyondTheMemoryNamingBothNumbers) {
  CostEstimate e;
  e.seconds = 1;
  e.bytes = 5e9;
  e.knot_cells = 99;
  e.cells_exact = true;
  try {
    refuse_if_too_costly(e, 100, 1e9);
    FAIL() << "not refused";
  } catch (const InputError& err) {
    const std::string what = err.what();
    EXPECT_NE(what.find("5e+03 MB"), std::string::npos) << what;
    EXPECT_NE(what.find("1e+03 MB of --max-memory"), std::string::npos) << what;
  }
  EXPECT_NO_THROW(refuse_if_too_costly(e, 100, 1e10));
  // Without a limit the machine's available memory is the limit.
  ASSERT_GT(support::available_memory_bytes(), 0);
  e.bytes = support::available_memory_bytes() * 2;
  try {
    refuse_if_too_costly(e, 100);
    FAIL() << "not refused";
  } catch (const InputError& err) {
    EXPECT_NE(std::string(err.what()).find("MemAvailable"), std::string::npos) << err.what();
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

// Thirteen directions whose knot cells number up to 1.05e7 (the general-position
// bound) were enumerated for 126 s and 5.5 GB before the cost check said "too costly", and under a
// 4 GB limit ended in std::bad_alloc. The refusal now comes first, on the prediction `--estimate`
// prints: its message says "at most", which only the bound (never the enumerated count) gives.
TEST(CostEstimate, DerivationBeyondTheBoundIsRefusedBeforeEnumerating) {
  const BoxSplineSpec spec = parse_spec(
      "1,0,0;0,1,0;0,0,1;1,1,1;1,1,-1;1,-1,1;-1,1,1;1,1,0;1,0,1;0,1,1;1,-1,0;1,0,-1;0,1,-1",
      "cartesian");
  try {
    (void)derive(spec);
    FAIL() << "derived";
  } catch (const InputError& err) {
    const std::string what = err.what();
    EXPECT_NE(what.find("too costly to derive exactly"), std::string::npos) << what;
    EXPECT_NE(what.find(" knot cells at most"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace boxgen::generator
