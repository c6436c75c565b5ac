// The expression graph (generator/codegen/ir/expr.h): hash-consing and exact evaluation.
#include <gtest/gtest.h>

#include "generator/codegen/ir/expr.h"
#include "generator/codegen/ir/expr_schedule.h"
#include "generator/codegen/ir/expr_simplify.h"
#include "generator/codegen/targets/expr_print.h"

namespace boxgen::expr {
namespace {

using generator::fraction;

TEST(ExprGraph, EqualSubexpressionsAreOneNode) {
  ExprGraph g;
  const NodeId x = g.variable(0), v = g.load(3);
  EXPECT_EQ(g.variable(0), x);
  EXPECT_EQ(g.constant(fraction(1, 3)), g.constant(fraction(2, 6)));
  const NodeId a = g.make(Op::Add, x, v);
  EXPECT_EQ(g.make(Op::Add, v, x), a);  // sums and products commute
  EXPECT_EQ(g.make(Op::Mul, g.make(Op::Add, v, x), x), g.make(Op::Mul, x, a));
  EXPECT_NE(g.make(Op::Mul, x, v), a);
  const std::size_t size = g.size();
  g.make(Op::Neg, a);
  g.make(Op::Neg, a);
  EXPECT_EQ(g.size(), size + 1);
}

// value = s * x, gradient = (s, 2 s): s = v0 + v1 is shared by all three and named once; the

// gradient block adds only what the value did not compute.

TEST(ExprGraph, EvaluatesExactly) {
  ExprGraph g;
  const NodeId x = g.variable(0), y = g.variable(1);
  const NodeId e = sum(g, product(g, scaled(g, fraction(1, 6), x), y), negate(g, g.load(0)));
  const auto values = evaluate_exactly(g, {fraction(3, 7), fraction(-2, 5)}, {fraction(11, 13)});
  EXPECT_EQ(values[e], fraction(1, 6) * fraction(3, 7) * fraction(-2, 5) - fraction(11, 13));
}

}  // namespace
}  // namespace boxgen::expr
