// The expression graph's passes one by one (generator/expr*.h): hash-consing, the simplifier's
// rules, the schedule's blocks, temporaries and counts, the printers, and exact evaluation.
#include <gtest/gtest.h>

#include "generator/expr.h"
#include "generator/expr_print.h"
#include "generator/expr_schedule.h"
#include "generator/expr_simplify.h"

namespace boxgen::generator {
namespace {

Rational q(long p, long r = 1) { return Rational(p) / Rational(r); }

TEST(ExprGraph, EqualSubexpressionsAreOneNode) {
  ExprGraph g;
  const NodeId x = g.variable(0), v = g.load(3);
  EXPECT_EQ(g.variable(0), x);
  EXPECT_EQ(g.constant(q(1, 3)), g.constant(q(2, 6)));
  const NodeId a = g.make(Op::Add, x, v);
  EXPECT_EQ(g.make(Op::Add, v, x), a);  // sums and products commute
  EXPECT_EQ(g.make(Op::Mul, g.make(Op::Add, v, x), x), g.make(Op::Mul, x, a));
  EXPECT_NE(g.make(Op::Mul, x, v), a);
  const std::size_t size = g.size();
  g.make(Op::Neg, a);
  g.make(Op::Neg, a);
  EXPECT_EQ(g.size(), size + 1);
}

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

// value = s * x, gradient = (s, 2 s): s = v0 + v1 is shared by all three and named once; the
// gradient block adds only what the value did not compute.
TEST(ExprSchedule, SharedNodesBecomeTemporariesInTheFirstBlockThatNeedsThem) {
  ExprGraph g;
  const NodeId x = g.variable(0), y = g.variable(1);
  const NodeId s = sum(g, g.load(0), g.load(1));
  const NodeId value = product(g, s, x);
  const NodeId dy = scaled(g, q(2), s);
  const NodeId dyy = sum(g, dy, y);
  Outputs out{value, {s, dy}, {g.constant(0), dyy, difference(g, x, dyy)}};
  const Program p = schedule(std::move(g), out, 2, {{s, "c0"}});
  ASSERT_EQ(p.blocks[0].temporaries.size(), 1u);
  EXPECT_EQ(p.blocks[0].temporaries[0].name, "c0");
  // dy is used by d[1] and by dyy: a temporary of the gradient block; dyy by two Hessian entries.
  ASSERT_EQ(p.blocks[1].temporaries.size(), 1u);
  EXPECT_EQ(p.blocks[1].temporaries[0].name, "t0");
  ASSERT_EQ(p.blocks[2].temporaries.size(), 1u);
  // value: 1 add (s) + 1 mul; gradient adds 1 mul; Hessian adds dyy (1 add) and x - dyy (1 add).
  EXPECT_EQ(p.cost[0], (OperationCount{1, 1, 0, 2, 1}));
  EXPECT_EQ(p.cost[1], (OperationCount{1, 2, 0, 2, 2}));
  EXPECT_EQ(p.cost[2], (OperationCount{3, 2, 0, 2, 3}));
  EXPECT_EQ(p.cost[2].total(), 5);
}

TEST(ExprPrint, WritesNegationsAsSubtractionsAndKeepsTheTree) {
  ExprGraph g;
  const NodeId x = g.variable(0), v = g.load(2);
  const NodeId shifted = sum(g, x, g.constant(-1));
  const NodeId value = difference(g, product(g, shifted, sum(g, v, g.load(0))), product(g, x, v));
  const NodeId d0 = negate(g, shifted);
  Outputs out{value, {d0}, {g.constant(q(1, 3))}};
  const Program p = schedule(std::move(g), out, 1);
  EXPECT_EQ(print_expression(p, value, cpp_syntax()),
            "t0 * (v[2] + v[0]) - x[0] * v[2]");
  EXPECT_EQ(p.blocks[0].temporaries.at(0).name, "t0");
  EXPECT_EQ(print_expression(p, d0, cpp_syntax()), "-t0");
  EXPECT_EQ(p.cost[1].negs, 1);
  const std::string body = print_cpp_body(p);
  EXPECT_NE(body.find("const T t0 = x[0] - T(1);"), std::string::npos) << body;
  EXPECT_NE(body.find("d[1] = T(0.33333333333333331);"), std::string::npos) << body;
  EXPECT_NE(body.find("if constexpr (Order >= 2)"), std::string::npos);
  const std::string glsl = print_straight_line(p, 2, glsl_syntax(false), "  ");
  EXPECT_NE(glsl.find("float t0 = x[0] - 1.0;"), std::string::npos) << glsl;
  EXPECT_NE(glsl.find("d[1] = 0.333333343;"), std::string::npos) << glsl;
  EXPECT_NE(glsl.find("return t0 * (v[2] + v[0]) - x[0] * v[2];"), std::string::npos) << glsl;
  const std::string glsl_double = print_straight_line(p, 0, glsl_syntax(true), "");
  EXPECT_NE(glsl_double.find("double t0 = x[0] - 1.0LF;"), std::string::npos) << glsl_double;
  EXPECT_EQ(glsl_double.find("d["), std::string::npos);  // the value path writes no derivative
}

TEST(ExprGraph, EvaluatesExactly) {
  ExprGraph g;
  const NodeId x = g.variable(0), y = g.variable(1);
  const NodeId e = sum(g, product(g, scaled(g, q(1, 6), x), y), negate(g, g.load(0)));
  const auto values = evaluate_exactly(g, {q(3, 7), q(-2, 5)}, {q(11, 13)});
  EXPECT_EQ(values[e], q(1, 6) * q(3, 7) * q(-2, 5) - q(11, 13));
}

}  // namespace
}  // namespace boxgen::generator
