#include "generator/polynomial_code.h"

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <map>

#include "generator/bbform.h"
#include "generator/code_text.h"
#include "generator/embedded_templates.h"
#include "generator/error.h"
#include "generator/linear_cse.h"
#include "generator/separable_form.h"

namespace boxgen::generator {

using code::count_operations;
using code::join;
using code::literal;

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

// ---- Coefficients of the monomials: fixed rational combinations of the stencil values. ----

// sum_i w_i x_i over named inputs; with `grouped`, inputs sharing |w| share one multiplication.
std::string linear_combination(const LinearRow& row, const std::vector<std::string>& names,
                               bool grouped) {
  struct Group {
    Rational weight;  // > 0
    std::string sum;
    int count = 0;
  };
  std::vector<Group> groups;
  std::vector<std::string> terms;
  for (const auto& [input, w] : row) {
    if (!grouped) {
      terms.push_back(fmt::format("T({}) * {}", literal(w), names[input]));
      continue;
    }
    const Rational magnitude = cln::abs(w);
    const bool negative = cln::minusp(w);
    auto it = std::find_if(groups.begin(), groups.end(),
                           [&](const Group& g) { return g.weight == magnitude; });
    if (it == groups.end()) {
      groups.push_back({magnitude, fmt::format("{}{}", negative ? "-" : "", names[input]), 1});
    } else {
      it->sum += fmt::format(" {} {}", negative ? "-" : "+", names[input]);
      ++it->count;
    }
  }
  if (grouped)
    for (const auto& g : groups)
      terms.push_back(g.weight == 1  ? "(" + g.sum + ")"
                      : g.count == 1 ? fmt::format("T({}) * {}", literal(g.weight), g.sum)
                                     : fmt::format("T({}) * ({})", literal(g.weight), g.sum));
  return join(terms, " + ");
}

// Named linear combinations of the stencil values v[k]: "const T <name> = ...;" per row. `shared`
// groups equal weights and shares partial sums across rows (generator/linear_cse.h); otherwise
// every term is written out.
struct LinearCode {
  std::string definitions;
  OperationCount cost;
  std::size_t shared_sums = 0;
};

LinearCode linear_code(const std::vector<LinearRow>& rows,
                       const std::vector<std::string>& names_out, int inputs, bool shared) {
  LinearCode c;
  const SharedRows s = shared ? share_partial_sums(rows, inputs) : SharedRows{{}, rows};
  std::vector<std::string> names;
  for (int k = 0; k < inputs; ++k) names.push_back(fmt::format("v[{}]", k));
  for (std::size_t j = 0; j < s.temporaries.size(); ++j) {
    const SharedSum& t = s.temporaries[j];
    const std::string expr =
        t.r == 1    ? fmt::format("{} + {}", names[t.a], names[t.b])
        : t.r == -1 ? fmt::format("{} - {}", names[t.a], names[t.b])
                    : fmt::format("{} + T({}) * {}", names[t.a], literal(t.r), names[t.b]);
    names.push_back(fmt::format("s{}", j));
    c.definitions += fmt::format("  const T {} = {};\n", names.back(), expr);
    c.cost += count_operations(expr);
  }
  c.shared_sums = s.temporaries.size();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::string sum = linear_combination(s.rows[i], names, shared);
    c.definitions += fmt::format("  const T {} = {};\n", names_out[i], sum);
    c.cost += count_operations(sum);
  }
  return c;
}

struct Coefficients {
  std::vector<std::size_t> used;  // monomial indices with a non-zero coefficient
  std::string definitions;
  OperationCount cost;
  std::size_t shared_sums = 0;
};

// The coefficient of each monomial as a linear combination of the stencil values, shared (the
// Horner forms) or written out term by term (the monomial form).
Coefficients coefficients(const std::vector<Poly>& basis, int n, int degree, bool shared) {
  Coefficients c;
  std::vector<LinearRow> rows;
  std::vector<std::string> names;
  for (std::size_t m = 0; m < monomial_count(n, degree); ++m) {
    LinearRow row;
    for (std::size_t k = 0; k < basis.size(); ++k) {
      const auto& cs = basis[k].coefficients();
      if (m < cs.size() && !cln::zerop(cs[m])) row.emplace_back(static_cast<int>(k), cs[m]);
    }
    if (row.empty()) continue;
    c.used.push_back(m);
    names.push_back(fmt::format("c{}", m));
    rows.push_back(std::move(row));
  }
  LinearCode code = linear_code(rows, names, static_cast<int>(basis.size()), shared);
  c.definitions = std::move(code.definitions);
  c.cost = code.cost;
  c.shared_sums = code.shared_sums;
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

// The path costs of code that shares the coefficients: value, then each derivative added.
void assign_path_costs(OrbitCode& code, const OperationCount& shared, const OperationCount& value,
                       const std::vector<OperationCount>& derivatives, int n) {
  code.value = shared;
  code.value += value;
  code.gradient = code.value;
  for (int i = 0; i < n; ++i) code.gradient += derivatives[i];
  code.hessian = code.gradient;
  for (std::size_t i = n; i < derivatives.size(); ++i) code.hessian += derivatives[i];
}

// The derivative assignments "d[i] = ...;" of one order, each in its own text.
std::string derivative_block(const std::vector<std::string>& exprs, std::size_t from,
                             std::size_t to) {
  std::string out;
  for (std::size_t i = from; i < to; ++i)
    out += fmt::format("    d[{}] = {};\n", i, exprs[i].empty() ? "T(0)" : exprs[i]);
  if (!out.empty()) out.pop_back();
  return out;
}

// ---- monomial ----

std::string power_product(const Exponent& e, int n) {
  std::string out;
  for (int i = 0; i < n; ++i)
    if (e[i]) out += fmt::format(" * p[{}][{}]", i, e[i]);
  return out;
}

OrbitCode monomial_code(const ReferenceRegion& ref, int orbit, int n, int degree) {
  const auto& exps = monomial_exponents(n, degree);
  const Coefficients c = coefficients(ref.basis, n, degree, false);
  const auto derivatives = derivative_indices(n, 2);
  std::string value = "T(0)";
  std::vector<std::string> d_exprs(derivatives.size());
  for (std::size_t m : c.used) {
    value += fmt::format("\n      + c{}{}", m, power_product(exps[m], n));
    for (std::size_t k = 0; k < derivatives.size(); ++k) {
      Exponent lowered{0, 0, 0};
      const long factor = derivative_factor(exps[m], derivatives[k], lowered);
      if (!factor) continue;
      d_exprs[k] += fmt::format("{}T({}) * c{}{}", d_exprs[k].empty() ? "" : "\n        + ", factor,
                                m, power_product(lowered, n));
    }
  }
  OrbitCode code{EmissionStrategy::Monomial, "", {}, {}, {}, "", {}};
  std::vector<OperationCount> d_costs;
  for (const auto& e : d_exprs) d_costs.push_back(count_operations(e));
  OperationCount shared = c.cost;
  shared.muls += static_cast<long>(n) * degree;  // the table of powers
  assign_path_costs(code, shared, count_operations(value), d_costs, n);
  code.text = fmt::format(
      fmt::runtime(templates::orbit_monomial), fmt::arg("orbit", orbit),
      fmt::arg("vertices", orbit_vertices(ref)), fmt::arg("monomials", c.used.size()),
      fmt::arg("stencil", ref.stencil.size()), fmt::arg("coefficients", c.definitions),
      fmt::arg("gradient", derivative_block(d_exprs, 0, n)),
      fmt::arg("hessian", derivative_block(d_exprs, n, d_exprs.size())), fmt::arg("value", value));
  return code;
}

// ---- horner and shifted ----

// Nested Horner form of sum_e coefficient(e) x^e in the variables `vars` (emitted names), from
// `var` on: the outer variable is factored out power by power, the remaining ones recursively.
std::string horner(const std::map<Exponent, std::string>& terms, int var,
                   const std::vector<std::string>& vars) {
  if (terms.empty()) return "";
  const int n = static_cast<int>(vars.size());
  if (var == n) return terms.begin()->second;  // every exponent is used up: one term left
  std::map<int, std::map<Exponent, std::string>> by_power;
  for (const auto& [e, text] : terms) by_power[e[var]].emplace(e, text);
  const int top = by_power.rbegin()->first;
  std::string acc = horner(by_power[top], var + 1, vars);
  for (int a = top - 1; a >= 0; --a) {
    const auto it = by_power.find(a);
    const std::string inner = it == by_power.end() ? "" : horner(it->second, var + 1, vars);
    acc = fmt::format("{}{}{} * ({})", inner, inner.empty() ? "" : " + ", vars[var], acc);
  }
  return acc;
}

// The monomial coefficients of `basis` (shared partial sums), then the Horner forms of the
// polynomial and of its exact partial derivatives in the variables `vars`.
struct HornerParts {
  Coefficients coefficients;
  std::string value;
  std::vector<std::string> derivatives;  // gradient, then the Hessian's upper triangle
  OperationCount value_cost;
  std::vector<OperationCount> derivative_costs;
};

HornerParts horner_parts(const std::vector<Poly>& basis, int n, int degree,
                         const std::vector<std::string>& vars) {
  HornerParts h;
  const auto& exps = monomial_exponents(n, degree);
  h.coefficients = coefficients(basis, n, degree, true);
  const auto derivatives = derivative_indices(n, 2);
  std::map<Exponent, std::string> value_terms;
  std::vector<std::map<Exponent, std::string>> d_terms(derivatives.size());
  for (std::size_t m : h.coefficients.used) {
    value_terms.emplace(exps[m], fmt::format("c{}", m));
    for (std::size_t k = 0; k < derivatives.size(); ++k) {
      Exponent lowered{0, 0, 0};
      const long factor = derivative_factor(exps[m], derivatives[k], lowered);
      if (factor)
        d_terms[k].emplace(
            lowered, factor == 1 ? fmt::format("c{}", m) : fmt::format("T({}) * c{}", factor, m));
    }
  }
  for (const auto& t : d_terms) {
    h.derivatives.push_back(horner(t, 0, vars));
    h.derivative_costs.push_back(count_operations(h.derivatives.back()));
  }
  h.value = horner(value_terms, 0, vars);
  if (h.value.empty()) h.value = "T(0)";
  h.value_cost = count_operations(h.value);
  return h;
}

std::vector<std::string> coordinate_names(int n) {
  std::vector<std::string> vars;
  for (int i = 0; i < n; ++i) vars.push_back(fmt::format("x[{}]", i));
  return vars;
}

OrbitCode horner_code(const ReferenceRegion& ref, int orbit, int n, int degree) {
  const HornerParts h = horner_parts(ref.basis, n, degree, coordinate_names(n));
  OrbitCode code{EmissionStrategy::Horner, "", {}, {}, {}, "", {}};
  assign_path_costs(code, h.coefficients.cost, h.value_cost, h.derivative_costs, n);
  code.text = fmt::format(
      fmt::runtime(templates::orbit_horner), fmt::arg("orbit", orbit),
      fmt::arg("vertices", orbit_vertices(ref)), fmt::arg("monomials", h.coefficients.used.size()),
      fmt::arg("shared", h.coefficients.shared_sums), fmt::arg("stencil", ref.stencil.size()),
      fmt::arg("coefficients", h.coefficients.definitions),
      fmt::arg("gradient", derivative_block(h.derivatives, 0, n)),
      fmt::arg("hessian", derivative_block(h.derivatives, n, h.derivatives.size())),
      fmt::arg("value", h.value));
  return code;
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

// The shifted form about one origin o: the stencil polynomials rewritten exactly in y = x - o,
// y computed once (one subtraction per axis where o_i != 0).
struct ShiftedForm {
  RatVec origin;
  HornerParts parts;
  std::string shift;  // "const T y0 = x[0] - T(...);" lines
  OperationCount shift_cost;
};

ShiftedForm shifted_form(const ReferenceRegion& ref, const RatVec& origin, int n, int degree) {
  ShiftedForm f{origin, {}, "", {}};
  RatVec minus(n);
  for (int i = 0; i < n; ++i) minus[i] = -origin[i];
  std::vector<Poly> basis;
  for (const auto& p : ref.basis) basis.push_back(p.translated(minus));  // q(y) = p(y + o)
  std::vector<std::string> vars = coordinate_names(n);
  for (int i = 0; i < n; ++i)
    if (!cln::zerop(origin[i])) vars[i] = fmt::format("y{}", i);
  f.parts = horner_parts(basis, n, degree, vars);
  for (int i = 0; i < n; ++i) {
    // Only the coordinates the polynomial uses (every derivative's variables are the value's).
    if (cln::zerop(origin[i]) || f.parts.value.find(vars[i]) == std::string::npos) continue;
    const std::string expr = cln::minusp(origin[i])
                                 ? fmt::format("x[{}] + T({})", i, literal(-origin[i]))
                                 : fmt::format("x[{}] - T({})", i, literal(origin[i]));
    f.shift += fmt::format("  const T {} = {};\n", vars[i], expr);
    f.shift_cost += count_operations(expr);
  }
  return f;
}

// The cheapest origin's code; nullopt without a candidate (a region has points other than 0, so
// only a degenerate input gets there).
std::optional<OrbitCode> shifted_code(const ReferenceRegion& ref, int orbit, int n, int degree) {
  std::optional<OrbitCode> best;
  const std::vector<RatVec> origins = shift_origins(ref, n);
  for (const RatVec& o : origins) {
    const ShiftedForm f = shifted_form(ref, o, n, degree);
    OperationCount shared = f.shift_cost;
    shared += f.parts.coefficients.cost;
    OrbitCode code{EmissionStrategy::Shifted, "", {}, {}, {}, "", {}};
    assign_path_costs(code, shared, f.parts.value_cost, f.parts.derivative_costs, n);
    if (best && code.gradient.total() >= best->gradient.total()) continue;
    const HornerParts& h = f.parts;
    code.text = fmt::format(
        fmt::runtime(templates::orbit_shifted), fmt::arg("orbit", orbit),
        fmt::arg("vertices", orbit_vertices(ref)), fmt::arg("origin", code::vertex_text(o)),
        fmt::arg("candidates", origins.size()), fmt::arg("monomials", h.coefficients.used.size()),
        fmt::arg("shared", h.coefficients.shared_sums), fmt::arg("stencil", ref.stencil.size()),
        fmt::arg("coefficients", h.coefficients.definitions), fmt::arg("shift", f.shift),
        fmt::arg("gradient", derivative_block(h.derivatives, 0, n)),
        fmt::arg("hessian", derivative_block(h.derivatives, n, h.derivatives.size())),
        fmt::arg("value", h.value));
    code.form = "about " + code::vertex_text(o);
    best = std::move(code);
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

// f(x_axis) in Horner form.
std::string univariate_horner(const UnivariatePoly& f, int axis) {
  std::string acc = fmt::format("T({})", literal(f.back()));
  for (int a = static_cast<int>(f.size()) - 2; a >= 0; --a)
    acc = (cln::zerop(f[a]) ? "" : fmt::format("T({}) + ", literal(f[a]))) +
          fmt::format("x[{}] * ({})", axis, acc);
  return acc;
}

std::string names(const std::vector<int>& v) {
  std::string out;
  for (std::size_t i = 0; i < v.size(); ++i) out += (i ? "x" : "") + std::to_string(v[i]);
  return out;
}

// Straight-line code under construction: each definition is one line, its cost counted.
struct StraightLine {
  std::string text;
  OperationCount& cost;
  void define(const std::string& name, const std::string& expr) {
    text += fmt::format("    const T {} = {};\n", name, expr);
    cost += count_operations(expr);
  }
};

// A partial contraction: (derivative orders of the contracted axes, grid positions on the rest).
using ContractionKey = std::pair<std::vector<int>, std::vector<int>>;
// weight[i][a][o]: the name of the o-th derivative of axis i's a-th 1-D weight ("" when zero).
using WeightNames = std::vector<std::vector<std::vector<std::string>>>;

WeightNames define_weights(const TensorGrid& grid, std::size_t g, int n, int order,
                           StraightLine& code) {
  WeightNames weight(n);
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < grid.sizes[i]; ++a) {
      weight[i].emplace_back();
      for (int o = 0; o <= order; ++o) {
        const UnivariatePoly f = derivative(grid.weights[i][a], o);
        if (f.empty()) {
          weight[i][a].push_back("");
          continue;
        }
        const std::string name = fmt::format("w{}_{}_{}_{}", g, i, a, o);
        code.define(name,
                    f.size() == 1 ? fmt::format("T({})", literal(f[0])) : univariate_horner(f, i));
        weight[i][a].push_back(name);
      }
    }
  return weight;
}

// The stencil values of the grid, keyed by their position on every axis (nothing contracted).
std::map<ContractionKey, std::string> stencil_level(const TensorGrid& grid, int n) {
  std::map<ContractionKey, std::string> level;
  for (std::size_t flat = 0; flat < grid.stencil.size(); ++flat) {
    std::vector<int> position;
    std::size_t rest = flat;
    for (int i = 0; i < n; ++i) {
      position.push_back(static_cast<int>(rest % grid.sizes[i]));
      rest /= grid.sizes[i];
    }
    level[{{}, position}] = fmt::format("v[{}]", grid.stencil[flat]);
  }
  return level;
}

// Contracts the first remaining axis against its weights (each derivative order that keeps the
// total within `order`), defining one partial sum per resulting key.
std::map<ContractionKey, std::string> contract_axis(
    const std::map<ContractionKey, std::string>& level, const WeightNames& weight, std::size_t g,
    int axis, int order, StraightLine& code) {
  std::map<ContractionKey, std::vector<std::string>> terms;
  for (const auto& [key, name] : level) {
    const int a = key.second[0];
    const std::vector<int> rest(key.second.begin() + 1, key.second.end());
    int used = 0;
    for (int o : key.first) used += o;
    for (int o = 0; used + o <= order; ++o) {
      if (weight[axis][a][o].empty()) continue;
      std::vector<int> orders = key.first;
      orders.push_back(o);
      terms[{orders, rest}].push_back(weight[axis][a][o] + " * " + name);
    }
  }
  std::map<ContractionKey, std::string> next;
  for (const auto& [key, list] : terms) {
    const std::string name =
        fmt::format("s{}_{}_{}_{}", g, axis, names(key.first), names(key.second));
    code.define(name, join(list, " + "));
    next[key] = name;
  }
  return next;
}

// Straight-line code for the value and the derivatives up to `order`: 1-D weights per grid and
// axis, then the contraction axis by axis, sharing partial sums across derivatives.
std::string separable_body(const std::vector<TensorGrid>& grids, int n, int order,
                           OperationCount& cost) {
  StraightLine code{"", cost};
  std::map<Exponent, std::vector<std::string>> results;  // derivative -> one term per grid
  for (std::size_t g = 0; g < grids.size(); ++g) {
    const WeightNames weight = define_weights(grids[g], g, n, order, code);
    std::map<ContractionKey, std::string> level = stencil_level(grids[g], n);
    for (int axis = 0; axis < n; ++axis) level = contract_axis(level, weight, g, axis, order, code);
    for (const auto& [key, name] : level) {
      Exponent e{0, 0, 0};
      for (int i = 0; i < n; ++i) e[i] = key.first[i];
      results[e].push_back(name);
    }
  }
  auto sum_of = [&](const Exponent& e) {
    const auto it = results.find(e);
    if (it == results.end()) return std::string("T(0)");
    cost += count_operations(join(it->second, " + "));
    return join(it->second, " + ");
  };
  std::string out = std::move(code.text);
  out += fmt::format("    const T value = {};\n", sum_of(Exponent{0, 0, 0}));
  const auto derivatives = derivative_indices(n, order);
  for (std::size_t k = 0; k < derivatives.size(); ++k)
    out += fmt::format("    d[{}] = {};\n", k, sum_of(derivatives[k]));
  out += "    return value;";
  return out;
}

std::optional<OrbitCode> separable_code(const ReferenceRegion& ref, int orbit, int n) {
  const auto grids = separable_form(ref, n);
  if (!grids) return std::nullopt;
  OrbitCode code{EmissionStrategy::Separable, "", {}, {}, {}, "", {}};
  const std::string value = separable_body(*grids, n, 0, code.value);
  const std::string gradient = separable_body(*grids, n, 1, code.gradient);
  const std::string hessian = separable_body(*grids, n, 2, code.hessian);
  std::vector<std::string> shapes;
  for (const auto& g : *grids)
    shapes.push_back(join(
        [&] {
          std::vector<std::string> s;
          for (int x : g.sizes) s.push_back(std::to_string(x));
          return s;
        }(),
        "x"));
  code.text = fmt::format(fmt::runtime(templates::orbit_separable), fmt::arg("orbit", orbit),
                          fmt::arg("vertices", orbit_vertices(ref)),
                          fmt::arg("stencil", ref.stencil.size()), fmt::arg("grids", join(shapes)),
                          fmt::arg("value", value), fmt::arg("gradient", gradient),
                          fmt::arg("hessian", hessian));
  return code;
}

// ---- bernstein ----

// a[0] + sum_j a[j + 1] x_j as emitted text (unit weights without a multiplication).
std::string affine_text(const RatVec& a) {
  std::string out;
  for (std::size_t j = 0; j < a.size(); ++j) {
    if (cln::zerop(a[j])) continue;
    const Rational magnitude = cln::abs(a[j]);
    const std::string x = j == 0 ? "" : fmt::format("x[{}]", j - 1);
    const std::string term = j == 0           ? fmt::format("T({})", literal(magnitude))
                             : magnitude == 1 ? x
                                              : fmt::format("T({}) * {}", literal(magnitude), x);
    const bool negative = cln::minusp(a[j]);
    out += out.empty() ? (negative ? "-" : "") + term
                       : fmt::format(" {} {}", negative ? "-" : "+", term);
  }
  return out.empty() ? "T(0)" : out;
}

// Position of each multi-index of bb_multi_indices(n, d).
std::map<MultiIndex, std::size_t> index_of(int n, int d) {
  std::map<MultiIndex, std::size_t> out;
  const auto indices = bb_multi_indices(n, d);
  for (std::size_t i = 0; i < indices.size(); ++i) out.emplace(indices[i], i);
  return out;
}

// The names of the values of each de Casteljau level ("" where a value is zero).
using BBLevels = std::vector<std::vector<std::string>>;

// De Casteljau from the BB-coefficients `level0`: q^r_b = sum_i l_i q^(r-1)_(b + e_i) for
// r = 1..d, every level kept (d - 1 and d - 2 give the derivatives); the definitions are appended
// to `text` and counted in `cost`.
BBLevels casteljau_levels(const std::vector<std::string>& level0, int n, int degree,
                          std::string& text, OperationCount& cost) {
  BBLevels levels{level0};
  for (int r = 1; r <= degree; ++r) {
    const auto previous = index_of(n, degree - r + 1);
    const auto indices = bb_multi_indices(n, degree - r);
    std::vector<std::string> next(indices.size());
    for (std::size_t b = 0; b < indices.size(); ++b) {
      std::vector<std::string> terms;
      for (int i = 0; i <= n; ++i) {
        MultiIndex up = indices[b];
        ++up[i];
        const std::string& q = levels.back()[previous.at(up)];
        if (!q.empty()) terms.push_back(fmt::format("l{} * {}", i, q));
      }
      if (terms.empty()) continue;
      next[b] = fmt::format("q{}_{}", r, b);
      const std::string expr = join(terms, " + ");
      text += fmt::format("  const T {} = {};\n", next[b], expr);
      cost += count_operations(expr);
    }
    levels.push_back(std::move(next));
  }
  return levels;
}

// sum_b weight(b) q^level_b as emitted text ("" when zero).
std::string level_combination(const BBLevels& levels, int level, int n, int degree,
                              const std::function<Rational(const MultiIndex&)>& weight) {
  if (level < 0) return "";
  const auto indices = bb_multi_indices(n, degree - level);
  LinearRow row;
  std::vector<std::string> names;
  for (std::size_t b = 0; b < indices.size(); ++b) {
    const std::string& q = levels[level][b];
    const Rational w = weight(indices[b]);
    names.push_back(q);
    if (!q.empty() && !cln::zerop(w)) row.emplace_back(static_cast<int>(b), w);
  }
  return row.empty() ? "" : linear_combination(row, names, true);
}

// The gradient from level d - 1 and the Hessian's upper triangle from level d - 2, in the order
// of d[]: fixed rational combinations, since every grad(l_i) is constant.
std::vector<std::string> bb_derivatives(const BBLevels& levels, const std::vector<RatVec>& lambda,
                                        int n, int degree) {
  std::vector<std::string> d_exprs;
  const Rational dd = Rational(degree);
  for (int p = 0; p < n; ++p)
    d_exprs.push_back(level_combination(levels, degree - 1, n, degree, [&](const MultiIndex& b) {
      const int i = static_cast<int>(std::find(b.begin(), b.end(), 1) - b.begin());
      return dd * lambda[i][p + 1];
    }));
  for (int p = 0; p < n; ++p)
    for (int q = p; q < n; ++q)
      d_exprs.push_back(level_combination(levels, degree - 2, n, degree, [&](const MultiIndex& b) {
        // the ordered pairs (i, j) with e_i + e_j = b: grad(l_i)_p grad(l_j)_q summed
        std::vector<int> parts;
        for (int i = 0; i <= n; ++i)
          for (int k = 0; k < b[i]; ++k) parts.push_back(i);
        const int i = parts[0], j = parts[1];
        Rational sum = lambda[i][p + 1] * lambda[j][q + 1];
        if (i != j) sum = sum + lambda[j][p + 1] * lambda[i][q + 1];
        return dd * (dd - 1) * sum;
      }));
  return d_exprs;
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
  // Level 0: the non-zero BB-coefficients ("" marks a zero one).
  std::vector<std::string> level(simplex.indices.size());
  std::vector<LinearRow> rows;
  std::vector<std::string> row_names;
  for (std::size_t b = 0; b < simplex.indices.size(); ++b) {
    LinearRow row;
    for (std::size_t k = 0; k < simplex.weights[b].size(); ++k)
      if (!cln::zerop(simplex.weights[b][k]))
        row.emplace_back(static_cast<int>(k), simplex.weights[b][k]);
    if (row.empty()) continue;
    level[b] = fmt::format("b{}", b);
    row_names.push_back(level[b]);
    rows.push_back(std::move(row));
  }
  const LinearCode coefficients =
      linear_code(rows, row_names, static_cast<int>(ref.basis.size()), true);
  OperationCount shared = coefficients.cost;
  std::string barycentric;
  if (degree > 0)
    for (int i = 0; i <= n; ++i) {
      const std::string expr = affine_text(lambda[i]);
      barycentric += fmt::format("  const T l{} = {};\n", i, expr);
      shared += count_operations(expr);
    }
  std::string casteljau;
  const BBLevels levels = casteljau_levels(level, n, degree, casteljau, shared);
  const std::string value = levels.back()[0].empty() ? "T(0)" : levels.back()[0];
  const std::vector<std::string> d_exprs = bb_derivatives(levels, lambda, n, degree);
  std::vector<OperationCount> d_costs;
  for (const auto& e : d_exprs) d_costs.push_back(count_operations(e));
  OrbitCode code{EmissionStrategy::Bernstein, "", {}, {}, {}, "", {}};
  assign_path_costs(code, shared, {}, d_costs, n);
  code.text = fmt::format(
      fmt::runtime(templates::orbit_bernstein), fmt::arg("orbit", orbit),
      fmt::arg("vertices", orbit_vertices(ref)), fmt::arg("degree", degree),
      fmt::arg("count", rows.size()), fmt::arg("shared", coefficients.shared_sums),
      fmt::arg("stencil", ref.stencil.size()), fmt::arg("coefficients", coefficients.definitions),
      fmt::arg("barycentric", barycentric), fmt::arg("casteljau", casteljau),
      fmt::arg("gradient", derivative_block(d_exprs, 0, n)),
      fmt::arg("hessian", derivative_block(d_exprs, n, d_exprs.size())), fmt::arg("value", value));
  return code;
}

}  // namespace

std::optional<OrbitCode> orbit_code(const ReferenceRegion& ref, int orbit, int n, int degree,
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
    return *code;
  }
  std::optional<OrbitCode> best;
  std::vector<StrategyCost> considered;
  // Ties keep the earlier strategy: the newer forms replace a chosen one only when cheaper.
  for (auto s : {EmissionStrategy::Horner, EmissionStrategy::Separable, EmissionStrategy::Monomial,
                 EmissionStrategy::Shifted, EmissionStrategy::Bernstein}) {
    auto code = orbit_code(ref, orbit, n, degree, s);
    if (!code) continue;
    considered.push_back({s, code->value, code->gradient, code->hessian});
    if (!best || code->gradient.total() < best->gradient.total()) best = std::move(code);
  }
  best->considered = std::move(considered);
  return *best;
}

}  // namespace boxgen::generator
