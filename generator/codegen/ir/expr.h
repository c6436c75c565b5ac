// The expression graph of the emitted polynomial code (docs/design.md §15):
// immutable nodes (exact rational constants, coordinates x[i], stencil values v[k], binary sums
// and products, negations), hash-consed so that structurally equal subexpressions are one node.
// Every emission strategy builds into a graph, through the simplifying constructors of
// generator/codegen/ir/expr_simplify.h; generator/codegen/ir/expr_schedule.h orders it into
// straight-line code and counts it, and generator/codegen/targets/expr_print.h prints that code for
// each target.
#pragma once
#include <cstdint>
#include <map>
#include <unordered_map>
#include <vector>

#include "generator/rational.h"

namespace boxgen::expr {

// Exact constants are the generator's rationals.
using generator::Rational;
using generator::RatVec;

enum class Op : std::uint8_t { Constant, Variable, Load, Add, Mul, Neg };

using NodeId = int;

// Add and Mul have operands a <= b (both commute, so the order is canonical); Neg has a; Constant
// has `index` into the graph's constants, Variable the coordinate i of x[i], Load the k of v[k].
struct Node {
  Op op = Op::Constant;
  NodeId a = -1, b = -1;
  int index = -1;
};

class ExprGraph {
 public:
  // The leaves, each made once.
  NodeId constant(const Rational& c);
  NodeId variable(int i);
  NodeId load(int k);
  // The node op(a, b) exactly as given (no simplification; generator/codegen/ir/expr_simplify.h
  // builds through these): the existing node when an equal one exists.
  NodeId make(Op op, NodeId a, NodeId b = -1);

  const Node& node(NodeId id) const { return nodes_[static_cast<std::size_t>(id)]; }
  const Rational& constant_value(NodeId id) const;
  bool is_constant(NodeId id) const { return node(id).op == Op::Constant; }
  bool is_leaf(NodeId id) const;
  std::size_t size() const { return nodes_.size(); }

 private:
  struct Key {
    Op op;
    NodeId a, b;
    int index;
    bool operator==(const Key&) const = default;
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const;
  };
  NodeId intern(const Node& n);

  std::vector<Node> nodes_;
  std::vector<Rational> constants_;
  std::unordered_map<Key, NodeId, KeyHash> ids_;
  struct Less {
    bool operator()(const Rational& x, const Rational& y) const { return x < y; }
  };
  std::map<Rational, NodeId, Less> constant_ids_;
};

// The exact value of every node at coordinates x and stencil values v (the reference the tests
// compare the graph with: generator/codegen/ir/expr_schedule.h must not change what the graph
// computes).
std::vector<Rational> evaluate_exactly(const ExprGraph& g, const RatVec& x, const RatVec& v);

}  // namespace boxgen::expr
