// The simplify pass (generator/expr_simplify.h): constant folding, identities, negations, grouped
// weights.
#include <gtest/gtest.h>

#include "generator/expr.h"
#include "generator/expr_print.h"
#include "generator/expr_schedule.h"
#include "generator/expr_simplify.h"

namespace boxgen::generator {
namespace {

Rational q(long p, long r = 1) { return Rational(p) / Rational(r); }

TEST(ExprSimplify, FoldsConstantsAndIdentities) {
  ExprGraph g;
  const NodeId x = g.variable(0), zero = g.constant(0), one = g.constant(1);
  EXPECT_EQ(sum(g, g.constant(q(1, 2)), g.constant(q(1, 3))), g.constant(q(5, 6)));
  EXPECT_EQ(product(g, g.constant(q(2, 3)), g.constant(q(3, 4))), g.constant(q(1, 2)));
  EXPECT_EQ(product(g, x, one), x);
  EXPECT_EQ(product(g, zero, x), zero);
  EXPECT_EQ(sum(g, x, zero), x);
  EXPECT_EQ(negate(g, negate(g, x)), x);
  EXPECT_EQ(product(g, g.constant(-1), x), negate(g, x));
  EXPECT_EQ(sum(g, x, negate(g, x)), zero);
  // Negations move out of products and into constant factors; c (d x) = (c d) x.
  const NodeId y = g.variable(1);
  EXPECT_EQ(product(g, negate(g, x), y), negate(g, product(g, x, y)));
  EXPECT_EQ(scaled(g, q(3), negate(g, x)), scaled(g, q(-3), x));
  EXPECT_EQ(scaled(g, q(2), scaled(g, q(5), x)), scaled(g, q(10), x));
  EXPECT_EQ(sum(g, negate(g, x), negate(g, y)), negate(g, sum(g, x, y)));
  EXPECT_EQ(sum(g, negate(g, x), g.constant(2)), negate(g, sum(g, x, g.constant(-2))));
}

TEST(ExprSimplify, WeightedSumGroupsEqualWeights) {
  ExprGraph g;
  const NodeId a = g.load(0), b = g.load(1), c = g.load(2);
  // 1/2 a - 1/2 b + 3 c = 1/2 (a - b) + 3 c: two multiplications, two additions.
  const NodeId grouped = weighted_sum(g, {{a, q(1, 2)}, {c, q(3)}, {b, q(-1, 2)}});
  EXPECT_EQ(grouped, sum(g, scaled(g, q(1, 2), difference(g, a, b)), scaled(g, q(3), c)));
  const NodeId plain = term_by_term_sum(g, {{a, q(1, 2)}, {c, q(3)}, {b, q(-1, 2)}});
  EXPECT_NE(plain, grouped);
  for (const RatVec& v : {RatVec{q(1), q(2), q(3)}, RatVec{q(-5, 7), q(1, 3), q(2, 9)}}) {
    const auto values = evaluate_exactly(g, {}, v);
    const Rational expected = q(1, 2) * v[0] - q(1, 2) * v[1] + q(3) * v[2];
    EXPECT_EQ(values[grouped], expected);
    EXPECT_EQ(values[plain], expected);
  }
  EXPECT_EQ(weighted_sum(g, {}), g.constant(0));
}

}  // namespace
}  // namespace boxgen::generator
