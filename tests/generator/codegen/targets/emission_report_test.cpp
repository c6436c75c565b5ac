// The report text of an emission (generator/codegen/targets/emission_report.h), on costs written
// here; the costs of real filters: tests/generator/codegen/strategies/polynomial_code_test.cpp.
#include "generator/codegen/targets/emission_report.h"

#include <gtest/gtest.h>

#include <vector>

namespace boxgen::generator {
namespace {

OperationCount cost(long adds, long muls) {
  OperationCount c;
  c.adds = adds;
  c.muls = muls;
  c.negs = 5;  // not part of the total the report prints
  return c;
}

TEST(EmissionReport, StrategyDescriptionNamesTheFormWhereThereIsOne) {
  EXPECT_EQ(strategy_description(EmissionStrategy::Shifted, "about (1,1,1)"),
            "shifted about (1,1,1)");
  EXPECT_EQ(strategy_description(EmissionStrategy::Horner, ""), "horner");
}

TEST(EmissionReport, ConsideredTextListsValueGradientAndHessianTotalsInOrder) {
  const std::vector<StrategyCost> considered = {
      {EmissionStrategy::Horner, cost(100, 82), cost(200, 208), cost(300, 240)},
      {EmissionStrategy::Bernstein, cost(1, 2), cost(3, 4), cost(5, 6)}};
  EXPECT_EQ(considered_text(considered), "horner 182 / 408 / 540, bernstein 3 / 7 / 11");
  EXPECT_EQ(considered_text({}), "");
}

}  // namespace
}  // namespace boxgen::generator
