#include "generator/codegen/targets/expr_print.h"

#include <fmt/format.h>

#include "generator/codegen/targets/target_printer.h"

namespace boxgen::generator {

using expr::ExprGraph;
using expr::Node;
using expr::NodeId;
using expr::Op;
using expr::Program;

namespace {

bool is_inline(const Program& p, NodeId id) { return !p.graph.is_leaf(id) && !p.is_temporary(id); }

std::string print(const Program& p, NodeId id, const TargetPrinter& s, bool top);

// An operand, parenthesised where the operator it stands under binds tighter than its own.
std::string operand(const Program& p, NodeId id, const TargetPrinter& s,
                    bool parenthesise_products) {
  std::string text = print(p, id, s, false);
  if (!is_inline(p, id)) return text;
  const Op op = p.graph.node(id).op;
  return op == Op::Add || (parenthesise_products && op == Op::Mul) ? "(" + text + ")" : text;
}

std::string print(const Program& p, NodeId id, const TargetPrinter& s, bool top) {
  const ExprGraph& g = p.graph;
  const Node& n = g.node(id);
  if (!top && p.is_temporary(id)) return p.names.at(id);
  switch (n.op) {
    case Op::Constant:
      return s.literal(g.constant_value(id));
    case Op::Variable:
      return fmt::format("x[{}]", n.index);
    case Op::Load:
      return fmt::format("v[{}]", n.index);
    case Op::Neg:
      return "-" + operand(p, n.a, s, true);
    case Op::Add: {
      // The first operand is neither a negation nor a constant (the simplifier leaves at most
      // one of those in a sum): a negation is written as a subtraction, a negative constant too.
      NodeId a = n.a, b = n.b;
      if (g.is_constant(a) || g.node(a).op == Op::Neg) std::swap(a, b);
      const std::string left = print(p, a, s, false);
      if (g.node(b).op == Op::Neg) return left + " - " + operand(p, g.node(b).a, s, false);
      if (g.is_constant(b) && cln::minusp(g.constant_value(b)))
        return left + " - " + s.literal(-g.constant_value(b));
      return left + " + " + operand(p, b, s, false);
    }
    case Op::Mul: {
      NodeId a = n.a, b = n.b;
      if (g.is_constant(b)) std::swap(a, b);  // the constant factor first
      return operand(p, a, s, false) + " * " + operand(p, b, s, true);
    }
  }
  return "";
}

std::string output_target(int index) { return index < 0 ? "value" : fmt::format("d[{}]", index); }

std::string block_text(const Program& p, int b, const TargetPrinter& s, const std::string& indent) {
  std::string out;
  for (const auto& t : p.blocks[b].temporaries)
    out +=
        fmt::format("{}{}{} = {};\n", indent, s.declaration(), t.name, print(p, t.node, s, true));
  return out;
}

std::string outputs_text(const Program& p, int b, const TargetPrinter& s,
                         const std::string& indent) {
  std::string out;
  for (const auto& [index, id] : p.blocks[b].outputs)
    if (index >= 0)
      out += fmt::format("{}{} = {};\n", indent, output_target(index), print_expression(p, id, s));
  return out;
}

}  // namespace

std::string print_expression(const Program& p, NodeId id, const TargetPrinter& s) {
  return print(p, id, s, false);
}

std::string print_cpp_body(const Program& p, const TargetPrinter& s) {
  const NodeId value = p.blocks[0].outputs.at(0).second;
  std::string out =
      "  static_cast<void>(v);  // unused where the polynomial is constant\n"
      "  static_cast<void>(x);\n"
      "  static_cast<void>(d);  // unused on the value path\n";
  out += block_text(p, 0, s, "  ");
  out += fmt::format("  const T value = {};\n", print_expression(p, value, s));
  out += "  if constexpr (Order >= 1) {\n";
  out += block_text(p, 1, s, "    ") + outputs_text(p, 1, s, "    ");
  out += "    if constexpr (Order >= 2) {\n";
  out += block_text(p, 2, s, "      ") + outputs_text(p, 2, s, "      ");
  out += "    }\n  }\n  return value;\n";
  return out;
}

std::string print_straight_line(const Program& p, int order, const TargetPrinter& s,
                                const std::string& indent) {
  std::string out;
  for (int b = 0; b <= order; ++b) out += block_text(p, b, s, indent);
  for (int b = 1; b <= order; ++b) out += outputs_text(p, b, s, indent);
  out += fmt::format("{}return {};\n", indent,
                     print_expression(p, p.blocks[0].outputs.at(0).second, s));
  return out;
}

}  // namespace boxgen::generator
