// The schedule pass (generator/codegen/ir/expr_schedule.h): blocks per path, temporaries and
// counts.
#include <gtest/gtest.h>

#include "generator/codegen/ir/expr.h"
#include "generator/codegen/ir/expr_schedule.h"
#include "generator/codegen/ir/expr_simplify.h"
#include "generator/codegen/targets/expr_print.h"

namespace boxgen::expr {
namespace {

using generator::fraction;

TEST(ExprSchedule, SharedNodesBecomeTemporariesInTheFirstBlockThatNeedsThem) {
  ExprGraph g;
  const NodeId x = g.variable(0), y = g.variable(1);
  const NodeId s = sum(g, g.load(0), g.load(1));
  const NodeId value = product(g, s, x);
  const NodeId dy = scaled(g, fraction(2), s);
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

}  // namespace
}  // namespace boxgen::expr
