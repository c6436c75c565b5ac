#include "generator/codegen/targets/glsl_evaluator.h"

#include <fmt/args.h>
#include <fmt/format.h>

#include <cstdint>
#include <utility>

#include "generator/codegen/code_text.h"
#include "generator/codegen/targets/evaluator_tables.h"
#include "generator/codegen/targets/target_printer.h"
#include "generator/embedded_templates.h"

namespace boxgen::generator {

namespace {

using code::join;

// A template's fields, as text.
using Fields = TemplateFields;

// "+ a * name" terms of an integer combination, zeros left out; `first` without a leading "+".
std::string combination(const std::vector<std::pair<std::int64_t, std::string>>& terms,
                        bool first) {
  std::string text;
  for (const auto& [c, name] : terms) {
    if (c == 0) continue;
    const std::int64_t m = c < 0 ? -c : c;
    const std::string factor = m == 1 ? name : fmt::format("{} * {}", m, name);
    if (first)
      text = c < 0 ? "-" + factor : factor;
    else
      text += fmt::format(" {} {}", c < 0 ? '-' : '+', factor);
    first = false;
  }
  return text;
}

// The glue of templates/evaluator.glsl.fmt with its loops over coordinates, normals, stencil
// points and derivatives unrolled, so that the shader indexes each private and `const` array by
// constants only (docs/gpu.md, "No array indexed at run time").

struct Glue {
  const Derivation& a;
  const std::string& name;
  int n;             // the dimension
  std::string real;  // float or double
  std::string vec;   // vecN or dvecN
  std::string ivec;  // ivecN
  std::int64_t k;    // the scale of the fine lattice
  static std::string axis(int i) { return std::string(1, "xyzw"[i]); }
};

// The point's cube of the period: rep reduced by the Hermite basis (as evaluator_tables.h's cube
// index), and the cube's number.
void add_cube(const Glue& g, const std::vector<std::int64_t>& hermite_rows, Fields& out) {
  const auto reduced = [&](int j, int i) { return hermite_rows[j * g.n + i] / g.k; };
  out.emplace_back("times_scale", g.k == 1 ? "" : fmt::format(" * {}", g.k));
  out.emplace_back("divide_by_scale", g.k == 1 ? "" : fmt::format("\n  s /= {}({});", g.real, g.k));
  std::vector<std::string> reduction;
  for (int j = 0; j < g.n; ++j) {
    const std::int64_t diagonal = reduced(j, j);
    reduction.push_back(diagonal == 1 ? fmt::format("  q = rep.{};", Glue::axis(j))
                                      : fmt::format("  q = {}_floor_div(rep.{}, {});", g.name,
                                                    Glue::axis(j), diagonal));
    for (int i = j; i < g.n; ++i)
      if (const std::int64_t c = reduced(j, i); c != 0)
        reduction.push_back(fmt::format("  rep.{} {}= {};", Glue::axis(i), c < 0 ? '+' : '-',
                                        combination({{c < 0 ? -c : c, "q"}}, true)));
  }
  out.emplace_back("hermite_reduction", join(reduction, "\n"));
  std::string cube;
  for (int i = g.n - 1; i >= 0; --i) {
    const std::string rep = "rep." + Glue::axis(i);
    if (cube.empty())
      cube = rep;
    else if (reduced(i, i) == 1)
      cube = fmt::format("{} + {}", cube, rep);
    else
      cube = fmt::format("({}) * {} + {}", cube, reduced(i, i), rep);
  }
  out.emplace_back("cube_expression", cube);
}

// The normals' products with r, the key of r's cell (the slab of each normal), and the slabs'
// violation summed in nearest_cell.
void add_key(const Glue& g, const KnotPlaneKeys& keys, Fields& out) {
  const int normal_count = static_cast<int>(keys.planes.size());
  std::vector<std::string> products, index_terms, violations;
  for (int p = 0; p < normal_count; ++p) {
    std::vector<std::pair<std::int64_t, std::string>> terms;
    for (int i = 0; i < g.n; ++i) terms.emplace_back(keys.planes[p][i], "r." + Glue::axis(i));
    const std::string product = combination(terms, true);
    products.push_back(
        fmt::format("  key[{}] = {};", p, product.empty() ? g.real + "(0)" : product));
    for (int m = 1; m < keys.widths[p]; ++m)
      index_terms.push_back(fmt::format("(key[{}] >= {}({}) ? {} : 0)", p, g.real, keys.mins[p] + m,
                                        keys.strides[p]));
    violations.push_back(
        fmt::format("{0}_violation(key[{1}], {0}_kCellKeys[at + {1}])", g.name, p));
  }
  products.push_back(fmt::format("  key[{}] = {}(0);", normal_count, g.real));
  out.emplace_back("key_products", join(products, "\n"));
  out.emplace_back("key_index",
                   index_terms.empty() ? "0" : join(index_terms, " +\n              "));
  out.emplace_back("violation_sum",
                   violations.empty() ? g.real + "(0)" : join(violations, " +\n        "));
}

// The cell's map: one axis vector per reference coordinate, the origin of its stencil, the point
// in the reference frame, and the axes as a matrix's columns.
void add_cell_map(const Glue& g, Fields& out) {
  std::vector<std::string> map, reference_point, origin_terms, axes;
  std::string identity;
  for (int i = 0; i < g.n; ++i) identity += fmt::format("{}{}", i ? ", " : "", i);
  for (int i = 0; i < g.n; ++i) {
    map.push_back(fmt::format(
        "  int perm{1} = {0}_kCellPerm[cell * {2} + {1}], sign{1} = {0}_kCellSign[cell * {2} + "
        "{1}],\n      a{1} = {0}_kCellA[cell * {2} + {1}];\n"
        "  {3} axis{1} = sign{1} * {3}(equal({3}(perm{1}), {3}({4})));",
        g.name, i, g.n, g.ivec, identity));
    origin_terms.push_back(fmt::format(" - a{0} * axis{0}", i));
    reference_point.push_back(
        fmt::format("  xr[{0}] = {1}(a{0}) + dot({2}(axis{0}), y);", i, g.real, g.vec));
    axes.push_back(fmt::format("{}(axis{})", g.vec, i));
  }
  out.emplace_back("cell_map", join(map, "\n"));
  out.emplace_back("origin_terms", join(origin_terms, ""));
  out.emplace_back("reference_point", join(reference_point, "\n"));
  out.emplace_back("axes", join(axes));
}

// The stencil's fetches: one orbit's points are constants; with several, the orbit's row of the
// reference stencil table.
void add_stencil(const Glue& g, Fields& out) {
  const SplineStructure& s = g.a.structure;
  std::vector<std::string> fetches;
  if (s.references.size() == 1) {
    const auto& stencil = s.references[0].stencil;
    for (int p = 0; p < s.stencil_max; ++p) {
      std::vector<std::pair<std::int64_t, std::string>> terms;
      for (int i = 0; i < g.n; ++i)
        terms.emplace_back(p < static_cast<int>(stencil.size()) ? stencil[p][i] : 0,
                           "axis" + std::to_string(i));
      fetches.push_back(
          fmt::format("  v[{}] = {}_fetch(origin{});", p, g.name, combination(terms, false)));
    }
  } else {
    fetches.push_back(fmt::format("  int size = {0}_kOrbitStencilSize[orbit], row = orbit * {1};",
                                  g.name, s.stencil_max));
    for (int p = 0; p < s.stencil_max; ++p) {
      std::string j = "origin";
      for (int i = 0; i < g.n; ++i)
        j += fmt::format(" + {}_kReferenceStencil[(row + {}) * {} + {}] * axis{}", g.name, p, g.n,
                         i, i);
      fetches.push_back(
          fmt::format("  v[{0}] = {0} < size ? {1}_fetch({2}) : {3}(0);", p, g.name, j, g.real));
    }
  }
  out.emplace_back("stencil_fetches", join(fetches, "\n"));
}

// The orbit's derivatives (gradient, then the Hessian's upper triangle) as a vector and a
// symmetric matrix.
void add_derivatives(const Glue& g, Fields& out) {
  const int derivatives = g.n + g.n * (g.n + 1) / 2;
  out.emplace_back("zeros", join(std::vector<std::string>(derivatives, g.real + "(0)")));
  std::vector<std::string> gradient, hessian;
  for (int i = 0; i < g.n; ++i) gradient.push_back(fmt::format("ref[{}]", i));
  for (int col = 0; col < g.n; ++col)
    for (int row = 0; row < g.n; ++row) {
      const int i = std::min(row, col), j = std::max(row, col);
      hessian.push_back(fmt::format("ref[{}]", g.n + i * g.n - i * (i - 1) / 2 + (j - i)));
    }
  out.emplace_back("reference_gradient", join(gradient));
  out.emplace_back("reference_hessian", join(hessian));
}

Fields unrolled_glue(const Derivation& a, const std::string& name, const KnotPlaneKeys& keys,
                     const std::vector<std::int64_t>& hermite_rows, bool double_precision) {
  const int n = a.spec.dimension();
  const Glue g{a,
               name,
               n,
               double_precision ? "double" : "float",
               fmt::format("{}vec{}", double_precision ? "d" : "", n),
               fmt::format("ivec{}", n),
               a.structure.scale};
  Fields out{{"ivec", g.ivec}};
  add_cube(g, hermite_rows, out);
  add_key(g, keys, out);
  add_cell_map(g, out);
  add_stencil(g, out);
  add_derivatives(g, out);
  return out;
}

}  // namespace

GlslText glsl_evaluator(const Derivation& a, const std::string& banner, const std::string& name,
                        const std::vector<OrbitCode>& orbits,
                        const std::vector<std::string>& cost_lines, bool double_precision) {
  const int n = a.spec.dimension();
  const int derivatives = n + n * (n + 1) / 2;
  const std::string real = double_precision ? "double" : "float";
  const std::string prefix = double_precision ? "d" : "";
  const SplineStructure& s = a.structure;
  const GlslPrinter printer(name, n, s.stencil_max, double_precision);
  const KnotPlaneKeys keys = knot_plane_keys(a);
  const IntColumns hermite = hermite_basis(a);
  const CellTables t = cell_tables(a, keys, hermite);
  std::vector<std::string> centre;
  for (const auto& c : s.centre) centre.push_back(printer.literal(c));
  std::vector<std::int64_t> hermite_rows;  // row j holds column j of the basis, as in C++
  for (const auto& col : hermite) hermite_rows.insert(hermite_rows.end(), col.begin(), col.end());
  Fields fields;
  auto add = [&](const char* key, const auto& value) {
    fields.emplace_back(key, fmt::format("{}", value));
  };
  add("banner", banner);
  add("name", name);
  add("real", real);
  add("vec", fmt::format("{}vec{}", prefix, n));
  add("mat", fmt::format("{}mat{}", prefix, n));
  add("dimension", n);
  add("derivatives", derivatives);
  add("stencil_size", s.stencil_max);
  add("scale", s.scale);
  add("orbit_costs", join(cost_lines, "\n"));
  add("centre", join(centre));
  add("normal_count", keys.planes.size());
  add("lookup_size", keys.size());
  add("cell_count", t.cube.size());
  add("orbit_count", orbits.size());
  // One orbit: a constant, so that the compiler folds the reference stencil into the code.
  add("orbit_of_cell", orbits.size() == 1 ? std::string("0") : name + "_kCellOrbit[cell]");
  add("orbit_functions", printer.functions(orbits));
  add("orbit_dispatch", printer.dispatch(orbits.size()));
  for (const auto& [key, value] : unrolled_glue(a, name, keys, hermite_rows, double_precision))
    add(key, value);
  GlslPrinter::Tables tables = printer.tables(s, keys, t);
  const auto print = [&](const Fields& table_fields) {
    fmt::dynamic_format_arg_store<fmt::format_context> args;
    for (const Fields* f : {static_cast<const Fields*>(&fields), &table_fields})
      for (const auto& [key, value] : *f) args.push_back(fmt::arg(key, value));
    return fmt::vformat(templates::evaluator_glsl, args);
  };
  GlslText out;
  out.text = print(tables.constant);
  out.buffered = print(tables.buffered);
  out.block = std::move(tables.block);
  return out;
}

}  // namespace boxgen::generator
