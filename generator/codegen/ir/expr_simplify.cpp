#include "generator/codegen/ir/expr_simplify.h"

#include <algorithm>

namespace boxgen::expr {

namespace {

bool is_constant_equal(const ExprGraph& g, NodeId a, int value) {
  return g.is_constant(a) && g.constant_value(a) == value;
}

}  // namespace

NodeId negate(ExprGraph& g, NodeId a) {
  if (g.is_constant(a)) return g.constant(-g.constant_value(a));
  if (g.node(a).op == Op::Neg) return g.node(a).a;
  return g.make(Op::Neg, a);
}

NodeId sum(ExprGraph& g, NodeId a, NodeId b) {
  if (g.is_constant(a) && g.is_constant(b))
    return g.constant(g.constant_value(a) + g.constant_value(b));
  if (is_constant_equal(g, a, 0)) return b;
  if (is_constant_equal(g, b, 0)) return a;
  const Node na = g.node(a);  // copies: building may grow the graph
  const Node nb = g.node(b);
  if (na.op == Op::Neg && nb.op == Op::Neg) return negate(g, sum(g, na.a, nb.a));
  if ((na.op == Op::Neg && na.a == b) || (nb.op == Op::Neg && nb.a == a)) return g.constant(0);
  // -x + c = -(x - c): the printer writes every remaining negation in a sum as its subtraction.
  if (na.op == Op::Neg && g.is_constant(b))
    return negate(g, sum(g, na.a, g.constant(-g.constant_value(b))));
  if (nb.op == Op::Neg && g.is_constant(a))
    return negate(g, sum(g, nb.a, g.constant(-g.constant_value(a))));
  return g.make(Op::Add, a, b);
}

NodeId difference(ExprGraph& g, NodeId a, NodeId b) { return sum(g, a, negate(g, b)); }

NodeId product(ExprGraph& g, NodeId a, NodeId b) {
  if (g.is_constant(b)) std::swap(a, b);  // a constant factor first
  if (g.is_constant(a)) {
    const Rational c = g.constant_value(a);
    if (g.is_constant(b)) return g.constant(c * g.constant_value(b));
    if (c == 0) return a;
    if (c == 1) return b;
    if (c == -1) return negate(g, b);
    const Node nb = g.node(b);
    if (nb.op == Op::Neg) return product(g, g.constant(-c), nb.a);
    // c (d y) = (c d) y; make() orders operands by id, so d may stand on either side.
    if (nb.op == Op::Mul && g.is_constant(nb.a))
      return product(g, g.constant(c * g.constant_value(nb.a)), nb.b);
    if (nb.op == Op::Mul && g.is_constant(nb.b))
      return product(g, g.constant(c * g.constant_value(nb.b)), nb.a);
    return g.make(Op::Mul, a, b);
  }
  const Node na = g.node(a);  // copies: building may grow the graph
  const Node nb = g.node(b);
  if (na.op == Op::Neg) return negate(g, product(g, na.a, b));
  if (nb.op == Op::Neg) return negate(g, product(g, a, nb.a));
  return g.make(Op::Mul, a, b);
}

NodeId scaled(ExprGraph& g, const Rational& c, NodeId a) { return product(g, g.constant(c), a); }

NodeId weighted_sum(ExprGraph& g, const WeightedTerms& terms) {
  struct Group {
    Rational weight;  // > 0
    NodeId sum;
  };
  std::vector<Group> groups;
  for (const auto& [t, w] : terms) {
    if (w == 0) continue;
    const Rational magnitude = cln::abs(w);
    const NodeId signed_term = cln::minusp(w) ? negate(g, t) : t;
    auto it = std::find_if(groups.begin(), groups.end(),
                           [&](const Group& x) { return x.weight == magnitude; });
    if (it == groups.end())
      groups.push_back({magnitude, signed_term});
    else
      it->sum = sum(g, it->sum, signed_term);
  }
  NodeId out = g.constant(0);
  for (const auto& group : groups) out = sum(g, out, scaled(g, group.weight, group.sum));
  return out;
}

NodeId term_by_term_sum(ExprGraph& g, const WeightedTerms& terms) {
  NodeId out = g.constant(0);
  for (const auto& [t, w] : terms) out = sum(g, out, scaled(g, w, t));
  return out;
}

}  // namespace boxgen::expr
