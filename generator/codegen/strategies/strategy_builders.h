// What every emission strategy (polynomial_code.h) builds with: a graph under construction, the
// stencil values' fixed rational combinations (the monomial coefficients), the order of the
// derivatives in d[], and `finish`, which schedules the graph and records its counts. Each
// strategy is a file <name>_strategy.cpp beside this one; polynomial_code.cpp chooses between them.
#pragma once
#include <cstddef>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "generator/codegen/ir/expr.h"
#include "generator/codegen/ir/expr_simplify.h"
#include "generator/codegen/ir/linear_cse.h"
#include "generator/codegen/strategies/polynomial_code.h"

namespace boxgen::generator::strategies {

// Multi-indices of the derivatives an evaluation of `order` writes, in the order of d[]: the
// gradient (e_i), then the Hessian's upper triangle row by row (e_i + e_j, i <= j).
std::vector<Exponent> derivative_indices(int n, int order);

// The reference region's vertices as "(0,0,0) (1,0,0) ...", for the comment.
std::string orbit_vertices(const ReferenceRegion& ref);

// A graph under construction and the names it suggests for its temporaries.
struct Build {
  ExprGraph g;
  std::unordered_map<NodeId, std::string> hints;
  void name(NodeId id, const std::string& hint) {
    if (!g.is_leaf(id)) hints.emplace(id, hint);  // the first name of a shared node stays
  }
  NodeId zero() { return g.constant(0); }
  std::vector<NodeId> coordinates(int n) {
    std::vector<NodeId> x;
    for (int i = 0; i < n; ++i) x.push_back(g.variable(i));
    return x;
  }
};

// The outputs from the value and the nodes of derivative_indices(n, 2), scheduled, with the
// strategy's comment (filled in by each target's printer).
OrbitCode finish(Build&& b, EmissionStrategy strategy, NodeId value,
                 const std::vector<NodeId>& derivatives, int n, OrbitComment comment);

// One node per row: sum_i w_i x_i over the stencil values. `shared` first sums pairs of inputs
// that several rows hold in the same ratio (generator/codegen/ir/linear_cse.h, named s0, s1, ...),
// then groups equal weights; otherwise every term is multiplied by its weight.
std::vector<NodeId> linear_nodes(Build& b, const std::vector<LinearRow>& rows, int inputs,
                                 bool shared, std::size_t* shared_sums = nullptr);

struct Coefficients {
  std::map<Exponent, NodeId> node;  // the monomials with a non-zero coefficient
  std::size_t shared_sums = 0;
};

// The coefficient of each monomial as a linear combination of the stencil values, named c<m>.
Coefficients coefficients(Build& b, const std::vector<Poly>& basis, int n, int degree, bool shared);

// d^D x^e / dx^D = factor x^(e - D); factor 0 when some e_i < D_i.
long derivative_factor(const Exponent& e, const Exponent& d, Exponent& lowered);

}  // namespace boxgen::generator::strategies
