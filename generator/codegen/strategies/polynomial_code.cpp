#include "generator/codegen/strategies/polynomial_code.h"

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <map>
#include <tuple>
#include <unordered_map>

#include "generator/bbform.h"
#include "generator/codegen/code_text.h"
#include "generator/codegen/ir/expr_simplify.h"
#include "generator/codegen/ir/linear_cse.h"
#include "generator/codegen/strategies/separable_form.h"
#include "generator/embedded_templates.h"
#include "generator/error.h"

namespace boxgen::generator {

using code::join;

EmissionStrategy parse_strategy(std::string_view name) {
  if (name == "auto") return EmissionStrategy::Auto;
  if (name == "monomial") return EmissionStrategy::Monomial;
  if (name == "horner") return EmissionStrategy::Horner;
  if (name == "separable") return EmissionStrategy::Separable;
  if (name == "shifted") return EmissionStrategy::Shifted;
  if (name == "bernstein") return EmissionStrategy::Bernstein;
  fail_input("--strategy must be auto, horner, shifted, bernstein, separable or monomial, got '" +
             std::string(name.substr(0, 40)) + "'");
}

const char* strategy_name(EmissionStrategy s) {
  switch (s) {
    case EmissionStrategy::Auto:
      return "auto";
    case EmissionStrategy::Monomial:
      return "monomial";
    case EmissionStrategy::Horner:
      return "horner";
    case EmissionStrategy::Separable:
      return "separable";
    case EmissionStrategy::Shifted:
      return "shifted";
    case EmissionStrategy::Bernstein:
      return "bernstein";
  }
  return "?";
}

std::string strategy_description(EmissionStrategy strategy, const std::string& form) {
  return form.empty() ? strategy_name(strategy)
                      : fmt::format("{} {}", strategy_name(strategy), form);
}

std::string considered_text(const std::vector<StrategyCost>& considered) {
  std::vector<std::string> parts;
  for (const auto& c : considered)
    parts.push_back(fmt::format("{} {} / {} / {}", strategy_name(c.strategy), c.value.total(),
                                c.gradient.total(), c.hessian.total()));
  return join(parts);
}

namespace {

using generator::ExprGraph;
using generator::NodeId;
using generator::WeightedTerms;

// Multi-indices of the derivatives an evaluation of `order` writes, in the order of d[]: the
// gradient (e_i), then the Hessian's upper triangle row by row (e_i + e_j, i <= j).
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

// The outputs from the value and the nodes of derivative_indices(n, 2), scheduled; the comment
// is the strategy's template filled in, the C++ function printed from the schedule.
OrbitCode finish(Build&& b, EmissionStrategy strategy, NodeId value,
                 const std::vector<NodeId>& derivatives, int n, std::string comment) {
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
  if (!comment.empty() && comment.back() == '\n') comment.pop_back();
  code.comment = std::move(comment);
  return code;
}

// ---- Coefficients: fixed rational combinations of the stencil values. ----

// One node per row: sum_i w_i x_i over the stencil values. `shared` first sums pairs of inputs
// that several rows hold in the same ratio (generator/codegen/ir/linear_cse.h, named s0, s1, ...),
// then groups equal weights; otherwise every term is multiplied by its weight.
std::vector<NodeId> linear_nodes(Build& b, const std::vector<LinearRow>& rows, int inputs,
                                 bool shared, std::size_t* shared_sums = nullptr) {
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

struct Coefficients {
  std::map<Exponent, NodeId> node;  // the monomials with a non-zero coefficient
  std::size_t shared_sums = 0;
};

// The coefficient of each monomial as a linear combination of the stencil values, named c<m>.
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

// d^D x^e / dx^D = factor x^(e - D); factor 0 when some e_i < D_i.
long derivative_factor(const Exponent& e, const Exponent& d, Exponent& lowered) {
  long factor = 1;
  for (int i = 0; i < 3; ++i) {
    if (e[i] < d[i]) return 0;
    for (int k = 0; k < d[i]; ++k) factor *= e[i] - k;
    lowered[i] = e[i] - d[i];
  }
  return factor;
}

// ---- monomial ----

OrbitCode monomial_code(const ReferenceRegion& ref, int orbit, int n, int degree) {
  Build b;
  const Coefficients c = coefficients(b, ref.basis, n, degree, false);
  // p[i][e] = x_i^e, and each monomial once.
  const std::vector<NodeId> x = b.coordinates(n);
  std::vector<std::vector<NodeId>> power(n, {b.g.constant(1)});
  for (int i = 0; i < n; ++i)
    for (int e = 1; e <= degree; ++e) {
      power[i].push_back(generator::product(b.g, power[i].back(), x[i]));
      b.name(power[i].back(), fmt::format("p{}_{}", i, e));
    }
  auto monomial = [&](const Exponent& e) {
    NodeId m = b.g.constant(1);
    for (int i = 0; i < n; ++i) m = generator::product(b.g, m, power[i][e[i]]);
    return m;
  };
  const auto derivatives = derivative_indices(n, 2);
  NodeId value = b.zero();
  std::vector<NodeId> d(derivatives.size(), b.zero());
  for (const auto& [e, coefficient] : c.node) {
    value = generator::sum(b.g, value, generator::product(b.g, coefficient, monomial(e)));
    for (std::size_t k = 0; k < derivatives.size(); ++k) {
      Exponent lowered{0, 0, 0};
      const long factor = derivative_factor(e, derivatives[k], lowered);
      if (!factor) continue;
      const NodeId term = generator::scaled(b.g, Rational(factor), coefficient);
      d[k] = generator::sum(b.g, d[k], generator::product(b.g, term, monomial(lowered)));
    }
  }
  return finish(
      std::move(b), EmissionStrategy::Monomial, value, d, n,
      fmt::format(fmt::runtime(templates::orbit_monomial), fmt::arg("orbit", orbit),
                  fmt::arg("vertices", orbit_vertices(ref)), fmt::arg("monomials", c.node.size()),
                  fmt::arg("stencil", ref.stencil.size())));
}

// ---- horner and shifted ----

// The nested Horner form of sum_e c_e y^e and of its partial derivatives, built so that the
// derivatives differentiate the Horner form itself: with P(prefix) the polynomial of the
// monomials whose exponents of y_0..y_(k-1) are the prefix (in y_k..y_(n-1)),
//   P(prefix) = sum_a y_k^a P(prefix, a), so
//   d^D P(prefix) = sum_(a >= D_k) a!/(a - D_k)! y_k^(a - D_k) d^(D without k) P(prefix, a),
// in Horner form in y_k. The inner d^D' P(prefix, a) are memoised: d/dy_0 reuses the value's
// inner polynomials, d^2/dy_0 dy_1 the gradient's d/dy_1 of them, and so on.
class HornerForm {
 public:
  HornerForm(Build& b, const std::map<Exponent, NodeId>& coefficients, std::vector<NodeId> vars)
      : b_(b), c_(coefficients), vars_(std::move(vars)), n_(static_cast<int>(vars_.size())) {}

  NodeId derivative(const Exponent& d) { return partial(Exponent{0, 0, 0}, 0, d); }

 private:
  // d^D P(prefix) where prefix fixes y_0..y_(k-1) and D_i = 0 for i < k.
  NodeId partial(const Exponent& prefix, int k, const Exponent& d) {
    if (k >= n_ || k >= 3) {  // (k < 3 spelled out for the compiler's bounds analysis)
      const auto it = c_.find(prefix);
      return it == c_.end() ? b_.zero() : it->second;
    }
    const auto key = std::make_tuple(prefix, k, d);
    const auto memo = memo_.find(key);
    if (memo != memo_.end()) return memo->second;
    int top = -1;  // the highest power of y_k under the prefix
    for (const auto& [e, node] : c_)
      if (std::equal(e.begin(), e.begin() + k, prefix.begin())) top = std::max(top, e[k]);
    Exponent rest = d;
    rest[k] = 0;
    NodeId acc = b_.zero();
    for (int a = top; a >= d[k]; --a) {
      Exponent next = prefix;
      next[k] = a;
      long factor = 1;
      for (int j = 0; j < d[k]; ++j) factor *= a - j;
      const NodeId term = generator::scaled(b_.g, Rational(factor), partial(next, k + 1, rest));
      acc = a == top ? term : generator::sum(b_.g, term, generator::product(b_.g, vars_[k], acc));
    }
    memo_.emplace(key, acc);
    return acc;
  }

  Build& b_;
  const std::map<Exponent, NodeId>& c_;
  std::vector<NodeId> vars_;
  int n_;
  std::map<std::tuple<Exponent, int, Exponent>, NodeId> memo_;
};

// The Horner form of the basis in the variables `vars`; value and derivative nodes returned.
struct HornerNodes {
  NodeId value;
  std::vector<NodeId> derivatives;
  std::size_t monomials = 0, shared_sums = 0;
};

HornerNodes horner_nodes(Build& b, const std::vector<Poly>& basis, int n, int degree,
                         const std::vector<NodeId>& vars) {
  const Coefficients c = coefficients(b, basis, n, degree, true);
  HornerForm form(b, c.node, vars);
  HornerNodes h{form.derivative({0, 0, 0}), {}, c.node.size(), c.shared_sums};
  for (const auto& e : derivative_indices(n, 2)) h.derivatives.push_back(form.derivative(e));
  return h;
}

OrbitCode horner_code(const ReferenceRegion& ref, int orbit, int n, int degree) {
  Build b;
  const HornerNodes h = horner_nodes(b, ref.basis, n, degree, b.coordinates(n));
  return finish(
      std::move(b), EmissionStrategy::Horner, h.value, h.derivatives, n,
      fmt::format(fmt::runtime(templates::orbit_horner), fmt::arg("orbit", orbit),
                  fmt::arg("vertices", orbit_vertices(ref)), fmt::arg("monomials", h.monomials),
                  fmt::arg("shared", h.shared_sums), fmt::arg("stencil", ref.stencil.size())));
}

// Candidate origins of the shifted form, exact points of the reference region: its centroid, its
// vertices, and the midpoints of every pair of vertices (edges, and diagonals of faces or of the
// region), without repeats and without 0 itself (monomials about 0 are the Horner form).
std::vector<RatVec> shift_origins(const ReferenceRegion& ref, int n) {
  std::vector<RatVec> out;
  auto add = [&](const RatVec& p) {
    const bool zero =
        std::all_of(p.begin(), p.end(), [](const Rational& r) { return cln::zerop(r); });
    if (!zero && std::find(out.begin(), out.end(), p) == out.end()) out.push_back(p);
  };
  RatVec centroid(n, Rational(0));
  for (const auto& v : ref.vertices)
    for (int i = 0; i < n; ++i)
      centroid[i] = centroid[i] + v[i] / Rational(static_cast<long>(ref.vertices.size()));
  add(centroid);
  for (const auto& v : ref.vertices) add(v);
  for (std::size_t a = 0; a < ref.vertices.size(); ++a)
    for (std::size_t b = a + 1; b < ref.vertices.size(); ++b) {
      RatVec mid(n);
      for (int i = 0; i < n; ++i) mid[i] = (ref.vertices[a][i] + ref.vertices[b][i]) / Rational(2);
      add(mid);
    }
  return out;
}

// The Horner form in y = x - o, the stencil polynomials rewritten exactly about o and
// y_i = x[i] - o_i computed once (named y<i>) where o_i != 0.
OrbitCode shifted_form(const ReferenceRegion& ref, const RatVec& origin, int orbit,
                       std::size_t candidates, int n, int degree) {
  Build b;
  RatVec minus(n);
  for (int i = 0; i < n; ++i) minus[i] = -origin[i];
  std::vector<Poly> basis;
  for (const auto& p : ref.basis) basis.push_back(p.translated(minus));  // q(y) = p(y + o)
  std::vector<NodeId> vars = b.coordinates(n);
  for (int i = 0; i < n; ++i) {
    vars[i] = generator::sum(b.g, vars[i], b.g.constant(-origin[i]));
    b.name(vars[i], fmt::format("y{}", i));
  }
  const HornerNodes h = horner_nodes(b, basis, n, degree, vars);
  OrbitCode code = finish(
      std::move(b), EmissionStrategy::Shifted, h.value, h.derivatives, n,
      fmt::format(fmt::runtime(templates::orbit_shifted), fmt::arg("orbit", orbit),
                  fmt::arg("vertices", orbit_vertices(ref)),
                  fmt::arg("origin", code::vertex_text(origin)), fmt::arg("candidates", candidates),
                  fmt::arg("monomials", h.monomials), fmt::arg("shared", h.shared_sums),
                  fmt::arg("stencil", ref.stencil.size())));
  code.form = "about " + code::vertex_text(origin);
  return code;
}

// The cheapest origin's code by value + gradient (the first among equals); nullopt without a
// candidate (a region has points other than 0, so only a degenerate input gets there).
std::optional<OrbitCode> shifted_code(const ReferenceRegion& ref, int orbit, int n, int degree) {
  std::optional<OrbitCode> best;
  const std::vector<RatVec> origins = shift_origins(ref, n);
  for (const RatVec& o : origins) {
    OrbitCode code = shifted_form(ref, o, orbit, origins.size(), n, degree);
    if (!best || code.gradient.total() < best->gradient.total()) best = std::move(code);
  }
  return best;
}

// ---- separable ----

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

// 1-D weights per grid and axis, then the contraction axis by axis; a partial sum is shared by
// every derivative that contracts it.
std::optional<OrbitCode> separable_code(const ReferenceRegion& ref, int orbit, int n) {
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
  return finish(
      std::move(b), EmissionStrategy::Separable, result({0, 0, 0}), d, n,
      fmt::format(fmt::runtime(templates::orbit_separable), fmt::arg("orbit", orbit),
                  fmt::arg("vertices", orbit_vertices(ref)),
                  fmt::arg("stencil", ref.stencil.size()), fmt::arg("grids", join(shapes))));
}

// ---- bernstein ----

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
                fmt::format(fmt::runtime(templates::orbit_bernstein), fmt::arg("orbit", orbit),
                            fmt::arg("vertices", orbit_vertices(ref)), fmt::arg("degree", degree),
                            fmt::arg("count", rows.size()), fmt::arg("shared", shared_sums),
                            fmt::arg("stencil", ref.stencil.size())));
}

std::optional<OrbitCode> strategy_code(const ReferenceRegion& ref, int orbit, int n, int degree,
                                       EmissionStrategy strategy) {
  switch (strategy) {
    case EmissionStrategy::Monomial:
      return monomial_code(ref, orbit, n, degree);
    case EmissionStrategy::Horner:
      return horner_code(ref, orbit, n, degree);
    case EmissionStrategy::Separable:
      return separable_code(ref, orbit, n);
    case EmissionStrategy::Shifted:
      return shifted_code(ref, orbit, n, degree);
    case EmissionStrategy::Bernstein:
      return bernstein_code(ref, orbit, n, degree);
    case EmissionStrategy::Auto:
      break;
  }
  return std::nullopt;
}

}  // namespace

std::optional<OrbitCode> orbit_code(const ReferenceRegion& ref, int orbit, int n, int degree,
                                    EmissionStrategy strategy) {
  return strategy_code(ref, orbit, n, degree, strategy);
}

namespace {

// Why a strategy does not apply to an orbit, as one line for the user.
std::string not_applicable(EmissionStrategy strategy, const ReferenceRegion& ref, int orbit,
                           int n) {
  switch (strategy) {
    case EmissionStrategy::Bernstein:
      return fmt::format(
          "--strategy bernstein: the reference region of orbit {} is not a simplex ({} vertices "
          "in {}-D)",
          orbit, ref.vertices.size(), n);
    case EmissionStrategy::Separable:
      return fmt::format(
          "--strategy separable: orbit {} is not a tensor product of univariate "
          "factors",
          orbit);
    default:
      return fmt::format("--strategy {}: no candidate origin for orbit {}", strategy_name(strategy),
                         orbit);
  }
}

}  // namespace

OrbitCode choose_orbit_code(const ReferenceRegion& ref, int orbit, int n, int degree,
                            EmissionStrategy strategy) {
  if (strategy != EmissionStrategy::Auto) {
    auto code = orbit_code(ref, orbit, n, degree, strategy);
    if (!code) fail_input(not_applicable(strategy, ref, orbit, n));
    return std::move(*code);
  }
  std::optional<OrbitCode> best;
  std::vector<StrategyCost> considered;
  // Ties keep the earlier strategy: the newer forms replace a chosen one only when cheaper.
  for (auto s : {EmissionStrategy::Horner, EmissionStrategy::Separable, EmissionStrategy::Monomial,
                 EmissionStrategy::Shifted, EmissionStrategy::Bernstein}) {
    auto code = strategy_code(ref, orbit, n, degree, s);
    if (!code) continue;
    considered.push_back({s, code->value, code->gradient, code->hessian});
    if (!best || code->gradient.total() < best->gradient.total()) best = std::move(code);
  }
  best->considered = std::move(considered);
  return std::move(*best);
}

}  // namespace boxgen::generator
