#include "generator/codegen/strategies/bernstein_strategy.h"

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <map>
#include <utility>
#include <vector>

#include "generator/bbform.h"
#include "generator/codegen/strategies/strategy_builders.h"
#include "generator/embedded_templates.h"

namespace boxgen::generator::strategies {

namespace {

// Position of each multi-index of bb_multi_indices(n, d).
std::map<MultiIndex, std::size_t> index_of(int n, int d) {
  std::map<MultiIndex, std::size_t> out;
  const auto indices = bb_multi_indices(n, d);
  for (std::size_t i = 0; i < indices.size(); ++i) out.emplace(indices[i], i);
  return out;
}

// The nodes of each de Casteljau level (0 where a value is zero).
using BBLevels = std::vector<std::vector<NodeId>>;

// De Casteljau from the BB-coefficients `level0`: q^r_b = sum_i l_i q^(r-1)_(b + e_i) for
// r = 1..d, every level kept (d - 1 and d - 2 give the derivatives).
BBLevels casteljau_levels(Build& b, const std::vector<NodeId>& level0, const std::vector<NodeId>& l,
                          int n, int degree) {
  BBLevels levels{level0};
  for (int r = 1; r <= degree; ++r) {
    const auto previous = index_of(n, degree - r + 1);
    const auto indices = bb_multi_indices(n, degree - r);
    std::vector<NodeId> next(indices.size());
    for (std::size_t q = 0; q < indices.size(); ++q) {
      NodeId acc = b.zero();
      for (int i = 0; i <= n; ++i) {
        MultiIndex up = indices[q];
        ++up[i];
        acc =
            generator::sum(b.g, acc, generator::product(b.g, l[i], levels.back()[previous.at(up)]));
      }
      next[q] = acc;
      b.name(acc, fmt::format("q{}_{}", r, q));
    }
    levels.push_back(std::move(next));
  }
  return levels;
}

// sum_b weight(b) q^level_b, values of equal weight grouped.
NodeId level_combination(Build& b, const BBLevels& levels, int level, int n, int degree,
                         const std::function<Rational(const MultiIndex&)>& weight) {
  if (level < 0) return b.zero();
  const auto indices = bb_multi_indices(n, degree - level);
  WeightedTerms terms;
  for (std::size_t q = 0; q < indices.size(); ++q)
    if (!b.g.is_constant(levels[level][q]) || !cln::zerop(b.g.constant_value(levels[level][q])))
      terms.emplace_back(levels[level][q], weight(indices[q]));
  return generator::weighted_sum(b.g, terms);
}

// The gradient from level d - 1 and the Hessian's upper triangle from level d - 2, in the order
// of d[]: fixed rational combinations, since every grad(l_i) is constant.
std::vector<NodeId> bb_derivatives(Build& b, const BBLevels& levels,
                                   const std::vector<RatVec>& lambda, int n, int degree) {
  std::vector<NodeId> d;
  const Rational dd = Rational(degree);
  for (int p = 0; p < n; ++p)
    d.push_back(level_combination(b, levels, degree - 1, n, degree, [&](const MultiIndex& m) {
      const int i = static_cast<int>(std::find(m.begin(), m.end(), 1) - m.begin());
      return dd * lambda[i][p + 1];
    }));
  for (int p = 0; p < n; ++p)
    for (int q = p; q < n; ++q)
      d.push_back(level_combination(b, levels, degree - 2, n, degree, [&](const MultiIndex& m) {
        // the ordered pairs (i, j) with e_i + e_j = m: grad(l_i)_p grad(l_j)_q summed
        std::vector<int> parts;
        for (int i = 0; i <= n; ++i)
          for (int k = 0; k < m[i]; ++k) parts.push_back(i);
        const int i = parts[0], j = parts[1];
        Rational sum = lambda[i][p + 1] * lambda[j][q + 1];
        if (i != j) sum = sum + lambda[j][p + 1] * lambda[i][q + 1];
        return dd * (dd - 1) * sum;
      }));
  return d;
}

}  // namespace

// On a simplicial reference region: the BB-coefficients (generator/bbform.h), the barycentric
// coordinates, de Casteljau's algorithm level by level (level r holds the degree d - r
// polynomials q_b, |b| = d - r, whose BB-combination with the degree-r Bernstein polynomials is
// p), and the derivatives from the last levels: grad p = d sum_i q_{e_i} grad(l_i) and
// Hess p = d (d - 1) sum_ij q_{e_i + e_j} grad(l_i) grad(l_j)^T, the gradients constant.
std::optional<OrbitCode> bernstein_code(const ReferenceRegion& ref, int orbit, int n, int degree) {
  if (static_cast<int>(ref.vertices.size()) != n + 1) return std::nullopt;
  const RegionBBForm bb = region_bb_form(ref, degree);
  const SimplexBBForm& simplex = bb.simplices.at(0);
  const std::vector<RatVec> lambda = barycentric_forms(simplex.vertices);
  Build b;
  // Level 0: the non-zero BB-coefficients.
  std::vector<LinearRow> rows;
  std::vector<std::size_t> nonzero;
  for (std::size_t q = 0; q < simplex.indices.size(); ++q) {
    LinearRow row;
    for (std::size_t k = 0; k < simplex.weights[q].size(); ++k)
      if (!cln::zerop(simplex.weights[q][k]))
        row.emplace_back(static_cast<int>(k), simplex.weights[q][k]);
    if (row.empty()) continue;
    nonzero.push_back(q);
    rows.push_back(std::move(row));
  }
  std::size_t shared_sums = 0;
  const auto coefficients =
      linear_nodes(b, rows, static_cast<int>(ref.basis.size()), true, &shared_sums);
  std::vector<NodeId> level(simplex.indices.size(), b.zero());
  for (std::size_t r = 0; r < nonzero.size(); ++r) {
    level[nonzero[r]] = coefficients[r];
    b.name(coefficients[r], fmt::format("b{}", nonzero[r]));
  }
  std::vector<NodeId> l;
  const std::vector<NodeId> x = b.coordinates(n);
  for (int i = 0; i <= n; ++i) {
    NodeId acc = b.g.constant(lambda[i][0]);
    for (int j = 0; j < n; ++j)
      acc = generator::sum(b.g, acc, generator::scaled(b.g, lambda[i][j + 1], x[j]));
    l.push_back(acc);
    b.name(acc, fmt::format("l{}", i));
  }
  const BBLevels levels = casteljau_levels(b, level, l, n, degree);
  const std::vector<NodeId> d = bb_derivatives(b, levels, lambda, n, degree);
  return finish(std::move(b), EmissionStrategy::Bernstein, levels.back()[0], d, n,
                {templates::orbit_bernstein,
                 {{"orbit", std::to_string(orbit)},
                  {"vertices", orbit_vertices(ref)},
                  {"degree", std::to_string(degree)},
                  {"count", std::to_string(rows.size())},
                  {"shared", std::to_string(shared_sums)},
                  {"stencil", std::to_string(ref.stencil.size())}}});
}

}  // namespace boxgen::generator::strategies
