#include "generator/codegen/strategies/strategy_builders.h"

#include <fmt/format.h>

#include <utility>

#include "generator/codegen/code_text.h"

namespace boxgen::generator::strategies {

using code::join;

std::vector<Exponent> derivative_indices(int n, int order) {
  std::vector<Exponent> out;
  if (order >= 1)
    for (int i = 0; i < n; ++i) {
      Exponent e{0, 0, 0};
      e[i] = 1;
      out.push_back(e);
    }
  if (order >= 2)
    for (int i = 0; i < n; ++i)
      for (int j = i; j < n; ++j) {
        Exponent e{0, 0, 0};
        ++e[i];
        ++e[j];
        out.push_back(e);
      }
  return out;
}

std::string orbit_vertices(const ReferenceRegion& ref) {
  std::vector<std::string> verts;
  for (const auto& v : ref.vertices) verts.push_back(code::vertex_text(v));
  return join(verts, " ");
}

OrbitCode finish(Build&& b, EmissionStrategy strategy, NodeId value,
                 const std::vector<NodeId>& derivatives, int n, OrbitComment comment) {
  generator::Outputs out;
  out.value = value;
  out.gradient.assign(derivatives.begin(), derivatives.begin() + n);
  out.hessian.assign(derivatives.begin() + n, derivatives.end());
  auto program = std::make_shared<const generator::Program>(
      generator::schedule(std::move(b.g), out, n, b.hints));
  OrbitCode code;
  code.strategy = strategy;
  code.program = program;
  code.value = program->cost[0];
  code.gradient = program->cost[1];
  code.hessian = program->cost[2];
  code.comment = std::move(comment);
  return code;
}

std::vector<NodeId> linear_nodes(Build& b, const std::vector<LinearRow>& rows, int inputs,
                                 bool shared, std::size_t* shared_sums) {
  const SharedRows s = shared ? share_partial_sums(rows, inputs) : SharedRows{{}, rows};
  std::vector<NodeId> input;
  for (int k = 0; k < inputs; ++k) input.push_back(b.g.load(k));
  for (std::size_t j = 0; j < s.temporaries.size(); ++j) {
    const SharedSum& t = s.temporaries[j];
    input.push_back(generator::sum(b.g, input[t.a], generator::scaled(b.g, t.r, input[t.b])));
    b.name(input.back(), fmt::format("s{}", j));
  }
  if (shared_sums) *shared_sums = s.temporaries.size();
  std::vector<NodeId> out;
  for (const auto& row : s.rows) {
    WeightedTerms terms;
    for (const auto& [i, w] : row) terms.emplace_back(input[i], w);
    out.push_back(shared ? generator::weighted_sum(b.g, terms)
                         : generator::term_by_term_sum(b.g, terms));
  }
  return out;
}

Coefficients coefficients(Build& b, const std::vector<Poly>& basis, int n, int degree,
                          bool shared) {
  Coefficients c;
  std::vector<LinearRow> rows;
  std::vector<std::size_t> used;
  for (std::size_t m = 0; m < monomial_count(n, degree); ++m) {
    LinearRow row;
    for (std::size_t k = 0; k < basis.size(); ++k) {
      const auto& cs = basis[k].coefficients();
      if (m < cs.size() && !cln::zerop(cs[m])) row.emplace_back(static_cast<int>(k), cs[m]);
    }
    if (row.empty()) continue;
    used.push_back(m);
    rows.push_back(std::move(row));
  }
  const auto nodes = linear_nodes(b, rows, static_cast<int>(basis.size()), shared, &c.shared_sums);
  const auto& exps = monomial_exponents(n, degree);
  for (std::size_t r = 0; r < used.size(); ++r) {
    b.name(nodes[r], fmt::format("c{}", used[r]));
    c.node.emplace(exps[used[r]], nodes[r]);
  }
  return c;
}

long derivative_factor(const Exponent& e, const Exponent& d, Exponent& lowered) {
  long factor = 1;
  for (int i = 0; i < 3; ++i) {
    if (e[i] < d[i]) return 0;
    for (int k = 0; k < d[i]; ++k) factor *= e[i] - k;
    lowered[i] = e[i] - d[i];
  }
  return factor;
}

}  // namespace boxgen::generator::strategies
