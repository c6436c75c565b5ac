#include "generator/codegen/ir/expr.h"

#include <functional>

namespace boxgen::expr {

std::size_t ExprGraph::KeyHash::operator()(const Key& k) const {
  std::size_t h = static_cast<std::size_t>(k.op);
  for (int part : {k.a, k.b, k.index}) h = h * 1000003u ^ std::hash<int>{}(part);
  return h;
}

NodeId ExprGraph::intern(const Node& n) {
  const Key key{n.op, n.a, n.b, n.index};
  const auto it = ids_.find(key);
  if (it != ids_.end()) return it->second;
  const auto id = static_cast<NodeId>(nodes_.size());
  nodes_.push_back(n);
  ids_.emplace(key, id);
  return id;
}

NodeId ExprGraph::constant(const Rational& c) {
  const auto it = constant_ids_.find(c);
  if (it != constant_ids_.end()) return it->second;
  constants_.push_back(c);
  const NodeId id = intern({Op::Constant, -1, -1, static_cast<int>(constants_.size()) - 1});
  constant_ids_.emplace(c, id);
  return id;
}

NodeId ExprGraph::variable(int i) { return intern({Op::Variable, -1, -1, i}); }

NodeId ExprGraph::load(int k) { return intern({Op::Load, -1, -1, k}); }

NodeId ExprGraph::make(Op op, NodeId a, NodeId b) {
  if ((op == Op::Add || op == Op::Mul) && b < a) std::swap(a, b);
  return intern({op, a, op == Op::Neg ? -1 : b, -1});
}

const Rational& ExprGraph::constant_value(NodeId id) const {
  return constants_[static_cast<std::size_t>(node(id).index)];
}

bool ExprGraph::is_leaf(NodeId id) const {
  const Op op = node(id).op;
  return op == Op::Constant || op == Op::Variable || op == Op::Load;
}

std::vector<Rational> evaluate_exactly(const ExprGraph& g, const RatVec& x, const RatVec& v) {
  // Operands are always made before the nodes that use them: one pass in id order.
  std::vector<Rational> value(g.size());
  for (std::size_t id = 0; id < g.size(); ++id) {
    const Node& n = g.node(static_cast<NodeId>(id));
    switch (n.op) {
      case Op::Constant:
        value[id] = g.constant_value(static_cast<NodeId>(id));
        break;
      case Op::Variable:
        value[id] = x.at(static_cast<std::size_t>(n.index));
        break;
      case Op::Load:
        value[id] = v.at(static_cast<std::size_t>(n.index));
        break;
      case Op::Add:
        value[id] = value[n.a] + value[n.b];
        break;
      case Op::Mul:
        value[id] = value[n.a] * value[n.b];
        break;
      case Op::Neg:
        value[id] = -value[n.a];
        break;
    }
  }
  return value;
}

}  // namespace boxgen::expr
