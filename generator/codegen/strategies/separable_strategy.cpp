#include "generator/codegen/strategies/separable_strategy.h"

#include <fmt/format.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "generator/codegen/code_text.h"
#include "generator/codegen/strategies/separable_form.h"
#include "generator/codegen/strategies/strategy_builders.h"
#include "generator/embedded_templates.h"

namespace boxgen::generator::strategies {

using code::join;

namespace {

UnivariatePoly derivative(UnivariatePoly f, int order) {
  for (int k = 0; k < order; ++k) {
    if (f.size() <= 1) return {};
    UnivariatePoly g(f.size() - 1);
    for (std::size_t a = 1; a < f.size(); ++a) g[a - 1] = f[a] * Rational(static_cast<long>(a));
    f = g;
  }
  bool zero = true;
  for (const auto& x : f) zero = zero && cln::zerop(x);
  return zero ? UnivariatePoly{} : f;
}

// f(x) in Horner form.
NodeId univariate_horner(Build& b, const UnivariatePoly& f, NodeId x) {
  NodeId acc = b.g.constant(f.back());
  for (int a = static_cast<int>(f.size()) - 2; a >= 0; --a)
    acc = generator::sum(b.g, b.g.constant(f[a]), generator::product(b.g, x, acc));
  return acc;
}

std::string names(const std::vector<int>& v) {
  std::string out;
  for (std::size_t i = 0; i < v.size(); ++i) out += (i ? "x" : "") + std::to_string(v[i]);
  return out;
}

// A partial contraction: (derivative orders of the contracted axes, grid positions on the rest).
using ContractionKey = std::pair<std::vector<int>, std::vector<int>>;
// weight[i][a][o]: the o-th derivative of axis i's a-th 1-D weight (-1 when zero).
using WeightNodes = std::vector<std::vector<std::vector<NodeId>>>;

WeightNodes define_weights(Build& b, const TensorGrid& grid, std::size_t g, int n) {
  WeightNodes weight(n);
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < grid.sizes[i]; ++a) {
      weight[i].emplace_back();
      for (int o = 0; o <= 2; ++o) {
        const UnivariatePoly f = derivative(grid.weights[i][a], o);
        weight[i][a].push_back(f.empty() ? -1 : univariate_horner(b, f, b.g.variable(i)));
        if (!f.empty()) b.name(weight[i][a].back(), fmt::format("w{}_{}_{}_{}", g, i, a, o));
      }
    }
  return weight;
}

// The stencil values of the grid, keyed by their position on every axis (nothing contracted).
std::map<ContractionKey, NodeId> stencil_level(Build& b, const TensorGrid& grid, int n) {
  std::map<ContractionKey, NodeId> level;
  for (std::size_t flat = 0; flat < grid.stencil.size(); ++flat) {
    std::vector<int> position;
    std::size_t rest = flat;
    for (int i = 0; i < n; ++i) {
      position.push_back(static_cast<int>(rest % grid.sizes[i]));
      rest /= grid.sizes[i];
    }
    level[{{}, position}] = b.g.load(grid.stencil[flat]);
  }
  return level;
}

// Contracts the first remaining axis against its weights (each derivative order that keeps the
// total within 2), one partial sum per resulting key.
std::map<ContractionKey, NodeId> contract_axis(Build& b,
                                               const std::map<ContractionKey, NodeId>& level,
                                               const WeightNodes& weight, std::size_t g, int axis) {
  std::map<ContractionKey, NodeId> next;
  for (const auto& [key, node] : level) {
    const int a = key.second[0];
    const std::vector<int> rest(key.second.begin() + 1, key.second.end());
    int used = 0;
    for (int o : key.first) used += o;
    for (int o = 0; used + o <= 2; ++o) {
      if (weight[axis][a][o] < 0) continue;
      std::vector<int> orders = key.first;
      orders.push_back(o);
      const NodeId term = generator::product(b.g, weight[axis][a][o], node);
      const auto [it, fresh] = next.emplace(ContractionKey{orders, rest}, term);
      if (!fresh) it->second = generator::sum(b.g, it->second, term);
    }
  }
  for (const auto& [key, node] : next)
    b.name(node, fmt::format("s{}_{}_{}_{}", g, axis, names(key.first), names(key.second)));
  return next;
}

}  // namespace

// 1-D weights per grid and axis, then the contraction axis by axis; a partial sum is shared by
// every derivative that contracts it.
std::optional<OrbitCode> separable_code(const ReferenceRegion& ref, int orbit, int n,
                                        int /*degree*/) {
  const auto grids = separable_form(ref, n);
  if (!grids) return std::nullopt;
  Build b;
  std::map<Exponent, NodeId> results;  // derivative -> the sum over grids
  for (std::size_t g = 0; g < grids->size(); ++g) {
    const WeightNodes weight = define_weights(b, (*grids)[g], g, n);
    std::map<ContractionKey, NodeId> level = stencil_level(b, (*grids)[g], n);
    for (int axis = 0; axis < n; ++axis) level = contract_axis(b, level, weight, g, axis);
    for (const auto& [key, node] : level) {
      Exponent e{0, 0, 0};
      for (int i = 0; i < n; ++i) e[i] = key.first[i];
      const auto [it, fresh] = results.emplace(e, node);
      if (!fresh) it->second = generator::sum(b.g, it->second, node);
    }
  }
  auto result = [&](const Exponent& e) {
    const auto it = results.find(e);
    return it == results.end() ? b.zero() : it->second;
  };
  std::vector<NodeId> d;
  for (const auto& e : derivative_indices(n, 2)) d.push_back(result(e));
  std::vector<std::string> shapes;
  for (const auto& g : *grids) {
    std::vector<std::string> s;
    for (int x : g.sizes) s.push_back(std::to_string(x));
    shapes.push_back(join(s, "x"));
  }
  return finish(std::move(b), EmissionStrategy::Separable, result({0, 0, 0}), d, n,
                {templates::orbit_separable,
                 {{"orbit", std::to_string(orbit)},
                  {"vertices", orbit_vertices(ref)},
                  {"stencil", std::to_string(ref.stencil.size())},
                  {"grids", join(shapes)}}});
}

}  // namespace boxgen::generator::strategies
