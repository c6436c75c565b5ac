// The schedule pass of the expression graph (generator/codegen/ir/expr.h): the outputs of one
// orbit's code (the value, the gradient, the Hessian's upper triangle) become three nested blocks
// of straight-line code, each holding only what its path adds to the one before (the value path;
// what the gradient needs beyond it; what the Hessian needs beyond both), so a node shared by the
// value, the gradient and the Hessian is computed once. A node used more than once becomes a
// named temporary; a node used once is written inline where it is used. Temporaries are ordered
// depth-first from the outputs (each defined just before the first expression that needs it,
// which keeps few values live). The costs are counted on the scheduled code, exactly as the
// printers (generator/codegen/targets/expr_print.h) write it.
#pragma once
#include <array>
#include <string>
#include <unordered_map>
#include <vector>

#include "generator/codegen/ir/expr.h"

namespace boxgen::expr {

// What one path of straight-line code costs: additions (and subtractions), multiplications,
// negations that remain after the simplifier moved them into subtractions and constants (none in
// the registry's code), distinct stencil values read, and named temporaries.
struct OperationCount {
  long adds = 0, muls = 0, negs = 0, loads = 0, temporaries = 0;
  long total() const { return adds + muls; }
  OperationCount& operator+=(const OperationCount& o) {
    adds += o.adds;
    muls += o.muls;
    negs += o.negs;
    loads += o.loads;
    temporaries += o.temporaries;
    return *this;
  }
  bool operator==(const OperationCount&) const = default;
};

// The results of an orbit function: the value and d[] (the gradient, then the Hessian's upper
// triangle row by row), as support::evaluate_located reads them.
struct Outputs {
  NodeId value = -1;
  std::vector<NodeId> gradient, hessian;
};

struct Statement {
  NodeId node;
  std::string name;
};

// Block 0 computes the value; block 1 (order >= 1) the gradient; block 2 (order >= 2) the Hessian.
// `outputs` holds (index into d[], node) for blocks 1 and 2 and (-1, value) for block 0.
struct Block {
  std::vector<Statement> temporaries;
  std::vector<std::pair<int, NodeId>> outputs;
};

struct Program {
  ExprGraph graph;
  int dimension = 0;
  std::array<Block, 3> blocks;
  std::unordered_map<NodeId, std::string> names;  // the temporaries' names
  std::array<OperationCount, 3> cost;             // whole paths: value; value + gradient; + Hessian

  bool is_temporary(NodeId id) const { return names.count(id) != 0; }
};

// Schedules the outputs; `hints` names some temporaries (c5 for a monomial coefficient, y0 for
// a shifted coordinate) and the others are t0, t1, ...
Program schedule(ExprGraph graph, const Outputs& outputs, int dimension,
                 const std::unordered_map<NodeId, std::string>& hints = {});

}  // namespace boxgen::expr
