// The print pass (generator/codegen/targets/expr_print.h) through the printers of
// generator/codegen/targets/target_printer.h: C++ and GLSL text of a scheduled graph.
#include <gtest/gtest.h>

#include "generator/codegen/ir/expr.h"
#include "generator/codegen/ir/expr_schedule.h"
#include "generator/codegen/ir/expr_simplify.h"
#include "generator/codegen/targets/expr_print.h"
#include "generator/codegen/targets/target_printer.h"

namespace boxgen::generator {
namespace {

using expr::ExprGraph;
using expr::NodeId;
using expr::Outputs;
using expr::Program;

TEST(ExprPrint, WritesNegationsAsSubtractionsAndKeepsTheTree) {
  ExprGraph g;
  const NodeId x = g.variable(0), v = g.load(2);
  const NodeId shifted = sum(g, x, g.constant(-1));
  const NodeId value = difference(g, product(g, shifted, sum(g, v, g.load(0))), product(g, x, v));
  const NodeId d0 = negate(g, shifted);
  Outputs out{value, {d0}, {g.constant(fraction(1, 3))}};
  const Program p = schedule(std::move(g), out, 1);
  EXPECT_EQ(print_expression(p, value, CppPrinter()), "t0 * (v[2] + v[0]) - x[0] * v[2]");
  EXPECT_EQ(p.blocks[0].temporaries.at(0).name, "t0");
  EXPECT_EQ(print_expression(p, d0, CppPrinter()), "-t0");
  EXPECT_EQ(p.cost[1].negs, 1);
  const std::string body = print_cpp_body(p, CppPrinter());
  EXPECT_NE(body.find("const T t0 = x[0] - T(1);"), std::string::npos) << body;
  EXPECT_NE(body.find("d[1] = T(0.33333333333333331);"), std::string::npos) << body;
  EXPECT_NE(body.find("if constexpr (Order >= 2)"), std::string::npos);
  const std::string glsl = print_straight_line(p, 2, GlslPrinter("f", 1, 3, false), "  ");
  EXPECT_NE(glsl.find("float t0 = x[0] - 1.0;"), std::string::npos) << glsl;
  EXPECT_NE(glsl.find("d[1] = 0.333333343;"), std::string::npos) << glsl;
  EXPECT_NE(glsl.find("return t0 * (v[2] + v[0]) - x[0] * v[2];"), std::string::npos) << glsl;
  const std::string glsl_double = print_straight_line(p, 0, GlslPrinter("f", 1, 3, true), "");
  EXPECT_NE(glsl_double.find("double t0 = x[0] - 1.0LF;"), std::string::npos) << glsl_double;
  EXPECT_EQ(glsl_double.find("d["), std::string::npos);  // the value path writes no derivative
}

}  // namespace
}  // namespace boxgen::generator
