// The simplify pass of the expression graph (generator/codegen/ir/expr.h), applied as each node is
// built, as GiNaC evaluates its expressions on construction: constants fold, x * 1, x * 0, x + 0
// and
// -(-x) vanish, a negation moves out of products and sums (into a constant factor where there is
// one) so that the printer writes it as a subtraction, and a weighted sum groups its terms of
// equal weight under one multiplication. What remains is hash-consed by ExprGraph::make.
#pragma once
#include <utility>
#include <vector>

#include "generator/codegen/ir/expr.h"

namespace boxgen::expr {

NodeId negate(ExprGraph& g, NodeId a);
NodeId sum(ExprGraph& g, NodeId a, NodeId b);
NodeId difference(ExprGraph& g, NodeId a, NodeId b);
NodeId product(ExprGraph& g, NodeId a, NodeId b);
// c * a for an exact constant c.
NodeId scaled(ExprGraph& g, const Rational& c, NodeId a);

// sum_i w_i t_i: terms of equal |w_i| summed (with their signs) before one multiplication by
// |w_i|, the groups then added in the order of their first terms. 0 for no terms.
using WeightedTerms = std::vector<std::pair<NodeId, Rational>>;
NodeId weighted_sum(ExprGraph& g, const WeightedTerms& terms);
// The same without grouping: one multiplication per term whose weight is not +-1.
NodeId term_by_term_sum(ExprGraph& g, const WeightedTerms& terms);

}  // namespace boxgen::expr
