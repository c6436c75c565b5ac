// The simplify pass (generator/codegen/ir/expr_simplify.h): constant folding, identities,
// negations, grouped weights.
#include <gtest/gtest.h>

#include "generator/codegen/ir/expr.h"
#include "generator/codegen/ir/expr_schedule.h"
#include "generator/codegen/ir/expr_simplify.h"
#include "generator/codegen/targets/expr_print.h"

namespace boxgen::expr {
namespace {

using generator::fraction;

TEST(ExprSimplify, FoldsConstantsAndIdentities) {
  ExprGraph g;
  const NodeId x = g.variable(0), zero = g.constant(0), one = g.constant(1);
  EXPECT_EQ(sum(g, g.constant(fraction(1, 2)), g.constant(fraction(1, 3))),
            g.constant(fraction(5, 6)));
  EXPECT_EQ(product(g, g.constant(fraction(2, 3)), g.constant(fraction(3, 4))),
            g.constant(fraction(1, 2)));
  EXPECT_EQ(product(g, x, one), x);
  EXPECT_EQ(product(g, zero, x), zero);
  EXPECT_EQ(sum(g, x, zero), x);
  EXPECT_EQ(negate(g, negate(g, x)), x);
  EXPECT_EQ(product(g, g.constant(-1), x), negate(g, x));
  EXPECT_EQ(sum(g, x, negate(g, x)), zero);
  // Negations move out of products and into constant factors; c (d x) = (c d) x.
  const NodeId y = g.variable(1);
  EXPECT_EQ(product(g, negate(g, x), y), negate(g, product(g, x, y)));
  EXPECT_EQ(scaled(g, fraction(3), negate(g, x)), scaled(g, fraction(-3), x));
  EXPECT_EQ(scaled(g, fraction(2), scaled(g, fraction(5), x)), scaled(g, fraction(10), x));
  EXPECT_EQ(sum(g, negate(g, x), negate(g, y)), negate(g, sum(g, x, y)));
  EXPECT_EQ(sum(g, negate(g, x), g.constant(2)), negate(g, sum(g, x, g.constant(-2))));
}

TEST(ExprSimplify, WeightedSumGroupsEqualWeights) {
  ExprGraph g;
  const NodeId a = g.load(0), b = g.load(1), c = g.load(2);
  // 1/2 a - 1/2 b + 3 c = 1/2 (a - b) + 3 c: two multiplications, two additions.
  const NodeId grouped =
      weighted_sum(g, {{a, fraction(1, 2)}, {c, fraction(3)}, {b, fraction(-1, 2)}});
  EXPECT_EQ(grouped,
            sum(g, scaled(g, fraction(1, 2), difference(g, a, b)), scaled(g, fraction(3), c)));
  const NodeId plain =
      term_by_term_sum(g, {{a, fraction(1, 2)}, {c, fraction(3)}, {b, fraction(-1, 2)}});
  EXPECT_NE(plain, grouped);
  for (const RatVec& v : {RatVec{fraction(1), fraction(2), fraction(3)},
                          RatVec{fraction(-5, 7), fraction(1, 3), fraction(2, 9)}}) {
    const auto values = evaluate_exactly(g, {}, v);
    const Rational expected = fraction(1, 2) * v[0] - fraction(1, 2) * v[1] + fraction(3) * v[2];
    EXPECT_EQ(values[grouped], expected);
    EXPECT_EQ(values[plain], expected);
  }
  EXPECT_EQ(weighted_sum(g, {}), g.constant(0));
}

}  // namespace
}  // namespace boxgen::expr
