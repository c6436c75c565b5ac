#include "generator/codegen/ir/expr_schedule.h"

#include <fmt/format.h>

#include <algorithm>
#include <set>

namespace boxgen::expr {

namespace {

// The outputs of block b, as (index into d[] or -1, node).
std::vector<std::pair<int, NodeId>> block_outputs(const Outputs& out, int b) {
  std::vector<std::pair<int, NodeId>> list;
  if (b == 0) list.emplace_back(-1, out.value);
  if (b == 1)
    for (std::size_t i = 0; i < out.gradient.size(); ++i)
      list.emplace_back(static_cast<int>(i), out.gradient[i]);
  if (b == 2)
    for (std::size_t i = 0; i < out.hessian.size(); ++i)
      list.emplace_back(static_cast<int>(out.gradient.size() + i), out.hessian[i]);
  return list;
}

std::vector<NodeId> operands(const Node& n) {
  switch (n.op) {
    case Op::Add:
    case Op::Mul:
      return {n.a, n.b};
    case Op::Neg:
      return {n.a};
    default:
      return {};
  }
}

// The operations of the expression that defines (or, inline, is) `id`: its own and those of its
// inline operands. A negation that is an operand of a sum is its subtraction, not an operation.
void count_expression(const Program& p, NodeId id, bool top, bool under_sum, OperationCount& c) {
  const ExprGraph& g = p.graph;
  if (g.is_leaf(id) || (!top && p.is_temporary(id))) return;
  const Node& n = g.node(id);
  if (n.op == Op::Add) ++c.adds;
  if (n.op == Op::Mul) ++c.muls;
  if (n.op == Op::Neg && !under_sum) ++c.negs;
  for (NodeId o : operands(n)) count_expression(p, o, false, n.op == Op::Add, c);
}

// A temporary's name: the builder's hint where it gave one, else t0, t1, ... (none a hint).
class TemporaryNames {
 public:
  explicit TemporaryNames(const std::unordered_map<NodeId, std::string>& hints) : hints_(hints) {
    for (const auto& [id, name] : hints) taken_.insert(name);
  }
  std::string operator()(NodeId id) {
    const auto hint = hints_.find(id);
    if (hint != hints_.end()) return hint->second;
    std::string name;
    do name = fmt::format("t{}", counter_++);
    while (taken_.count(name));
    return name;
  }

 private:
  const std::unordered_map<NodeId, std::string>& hints_;
  std::set<std::string> taken_;
  int counter_ = 0;
};

// The costs of the scheduled blocks, path by path (each path runs its block and those before);
// block[i] is the first block that needs node i.
void count_costs(Program& p, const std::vector<int>& block) {
  const ExprGraph& g = p.graph;
  std::set<NodeId> loads;
  OperationCount total;
  for (int b = 0; b < 3; ++b) {
    for (const auto& s : p.blocks[b].temporaries) {
      count_expression(p, s.node, true, false, total);
      ++total.temporaries;
    }
    for (const auto& [index, id] : p.blocks[b].outputs)
      count_expression(p, id, !p.is_temporary(id), false, total);
    for (std::size_t i = 0; i < block.size(); ++i)
      if (block[i] == b && g.node(static_cast<NodeId>(i)).op == Op::Load)
        loads.insert(static_cast<NodeId>(i));
    total.loads = static_cast<long>(loads.size());
    p.cost[b] = total;
  }
}

}  // namespace

Program schedule(ExprGraph graph, const Outputs& outputs, int dimension,
                 const std::unordered_map<NodeId, std::string>& hints) {
  Program p{std::move(graph), dimension, {}, {}, {}};
  const ExprGraph& g = p.graph;
  const std::size_t size = g.size();
  // The first block that needs each node (3: none), by a pass from the outputs down: operands
  // have smaller ids than the nodes that use them.
  std::vector<int> block(size, 3);
  std::vector<long> uses(size, 0);
  for (int b = 0; b < 3; ++b)
    for (const auto& [index, id] : block_outputs(outputs, b)) {
      block[id] = std::min(block[id], b);
      ++uses[id];
    }
  for (std::size_t i = size; i-- > 0;) {
    if (block[i] == 3) continue;
    const Node& n = g.node(static_cast<NodeId>(i));
    for (NodeId o : operands(n)) {
      block[o] = std::min(block[o], block[i]);
      // A negation is written inline wherever it is used, so its operand is used as often.
      uses[o] += n.op == Op::Neg ? uses[i] : 1;
    }
  }
  auto wants_name = [&](NodeId id) {
    return !g.is_leaf(id) && g.node(id).op != Op::Neg && uses[id] >= 2;
  };
  // Depth-first from each block's outputs: a temporary is defined after its operands.
  std::vector<char> placed(size, 0);
  TemporaryNames names(hints);
  for (int b = 0; b < 3; ++b) {
    Block& out = p.blocks[b];
    out.outputs = block_outputs(outputs, b);
    std::vector<std::pair<NodeId, bool>> stack;  // (node, operands done)
    for (auto it = out.outputs.rbegin(); it != out.outputs.rend(); ++it)
      stack.emplace_back(it->second, false);
    while (!stack.empty()) {
      const auto [id, done] = stack.back();
      stack.pop_back();
      if (placed[id]) continue;
      if (done) {
        placed[id] = 1;
        if (!wants_name(id)) continue;
        const std::string name = names(id);
        p.names.emplace(id, name);
        out.temporaries.push_back({id, name});
        continue;
      }
      stack.emplace_back(id, true);
      const auto ops = operands(g.node(id));
      for (auto o = ops.rbegin(); o != ops.rend(); ++o)
        if (!placed[*o]) stack.emplace_back(*o, false);
    }
  }
  count_costs(p, block);
  return p;
}

}  // namespace boxgen::expr
