#include "generator/glsl_evaluator.h"

#include <fmt/args.h>
#include <fmt/format.h>

#include <cstdint>
#include <utility>

#include "generator/code_text.h"
#include "generator/embedded_templates.h"
#include "generator/evaluator_tables.h"
#include "generator/expr_print.h"

namespace boxgen::generator {

namespace {

using code::join;

template <class V>
std::string flat(const V& values) {
  std::vector<std::string> parts;
  for (const auto& v : values) parts.push_back(fmt::format("{}", v));
  return join(parts);
}

template <class Rows>
std::string flat_rows(const Rows& rows) {
  std::vector<std::string> parts;
  for (const auto& row : rows) parts.push_back(flat(row));
  return join(parts, ",\n    ");
}

// A template's fields, as text.
using Fields = std::vector<std::pair<const char*, std::string>>;

template <class Rows>
std::vector<int> flat_ints(const Rows& rows) {
  std::vector<int> out;
  for (const auto& row : rows)
    for (const auto& v : row) out.push_back(static_cast<int>(v));
  return out;
}

// One int table of the evaluator: its template field, name, size as the text declares it, and
// entries (as the text lists them: one row per line where it has rows).
struct IntTable {
  const char* field;
  std::string name, size;
  std::string text;
  std::vector<int> values;
  bool run_time_indexed;
};

// The tables' declarations: in `text`, each a `const` array; in `buffered`, the run-time-indexed
// ones members of one read-only storage block at the place of the first (the others' lines left
// empty), whose contents are `block` (std430: int arrays, tightly packed, in order).
void add_tables(const std::string& name, const std::vector<IntTable>& tables, Fields& constant,
                Fields& buffered, std::vector<int>& block) {
  std::string members;
  for (const IntTable& t : tables)
    if (t.run_time_indexed) members += fmt::format("  int {}[{}];\n", t.name, t.values.size());
  bool first = true;
  for (const IntTable& t : tables) {
    const std::string declaration =
        fmt::format("const int {}[{}] = int[]({});", t.name, t.size, t.text);
    constant.emplace_back(t.field, declaration);
    if (!t.run_time_indexed) {
      buffered.emplace_back(t.field, declaration);
      continue;
    }
    buffered.emplace_back(
        t.field, first ? fmt::format("layout(std430, binding = BOXGEN_TABLES_BINDING) readonly "
                                     "buffer {}_Tables {{\n{}}};",
                                     name, members)
                       : std::string());
    block.insert(block.end(), t.values.begin(), t.values.end());
    first = false;
  }
}

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
  const Syntax syntax = glsl_syntax(double_precision);
  const SplineStructure& s = a.structure;
  const KnotPlaneKeys keys = knot_plane_keys(a);
  const IntColumns hermite = hermite_basis(a);
  const CellTables t = cell_tables(a, keys, hermite);
  std::vector<std::string> centre, functions, dispatch;
  for (const auto& c : s.centre) centre.push_back(syntax.literal(c));
  std::vector<std::int64_t> hermite_rows;  // row j holds column j of the basis, as in C++
  for (const auto& col : hermite) hermite_rows.insert(hermite_rows.end(), col.begin(), col.end());
  std::vector<int> sizes;
  for (const auto& r : s.references) sizes.push_back(static_cast<int>(r.stencil.size()));
  std::vector<std::vector<std::int64_t>> reference_stencil;
  for (const auto& r : s.references) {
    reference_stencil.emplace_back();
    for (int k = 0; k < s.stencil_max; ++k)
      for (int i = 0; i < n; ++i)
        reference_stencil.back().push_back(k < static_cast<int>(r.stencil.size()) ? r.stencil[k][i]
                                                                                  : 0);
  }
  for (std::size_t o = 0; o < orbits.size(); ++o) {
    std::string text = orbits[o].comment + "\n";
    for (int order = 0; order <= 2; ++order) {
      const std::string f = fmt::format("{}_orbit{}_{}", name, o, order);
      text += fmt::format("{0} {1}(in {0} v[{2}], in {0} x[{3}], inout {0} d[{4}]) {{\n{5}}}\n",
                          real, f, s.stencil_max, n, derivatives,
                          print_straight_line(*orbits[o].program, order, syntax, "  "));
      dispatch.push_back(
          fmt::format("  if (order == {} && o == {}) return {}(v, x, d);", order, o, f));
    }
    functions.push_back(text);
  }
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
  add("orbit_functions", join(functions, "\n"));
  add("orbit_dispatch", join(dispatch, "\n"));
  for (const auto& [key, value] : unrolled_glue(a, name, keys, hermite_rows, double_precision))
    add(key, value);
  // The tables indexed by the point's cell, and with several orbits by its orbit.
  const std::size_t cells = t.cube.size();
  const bool orbit_indexed = orbits.size() > 1;
  const std::vector<IntTable> tables{
      {"table_lookup", name + "_kLookup", fmt::format("{} * {}", t.lookup.size(), keys.size()),
       flat_rows(t.lookup), flat_ints(t.lookup), true},
      {"table_cell_cube", name + "_kCellCube", std::to_string(cells), flat(t.cube), t.cube, true},
      {"table_cell_orbit", name + "_kCellOrbit", std::to_string(cells), flat(t.orbit), t.orbit,
       true},
      {"table_cell_keys", name + "_kCellKeys",
       fmt::format("{} * ({} + 1)", cells, keys.planes.size()), flat_rows(t.keys),
       flat_ints(t.keys), true},
      {"table_cell_perm", name + "_kCellPerm", fmt::format("{} * {}", cells, n), flat_rows(t.perm),
       flat_ints(t.perm), true},
      {"table_cell_sign", name + "_kCellSign", fmt::format("{} * {}", cells, n), flat_rows(t.sign),
       flat_ints(t.sign), true},
      {"table_cell_a", name + "_kCellA", fmt::format("{} * {}", cells, n), flat_rows(t.a),
       flat_ints(t.a), true},
      {"table_orbit_stencil_size", name + "_kOrbitStencilSize", std::to_string(orbits.size()),
       flat(sizes), sizes, orbit_indexed},
      {"table_reference_stencil", name + "_kReferenceStencil",
       fmt::format("{} * {} * {}", orbits.size(), s.stencil_max, n), flat_rows(reference_stencil),
       flat_ints(reference_stencil), orbit_indexed}};
  Fields constant, buffered;
  GlslText out;
  add_tables(name, tables, constant, buffered, out.block);
  const auto print = [&](const Fields& table_fields) {
    fmt::dynamic_format_arg_store<fmt::format_context> args;
    for (const Fields* f : {static_cast<const Fields*>(&fields), &table_fields})
      for (const auto& [key, value] : *f) args.push_back(fmt::arg(key, value));
    return fmt::vformat(templates::evaluator_glsl, args);
  };
  out.text = print(constant);
  out.buffered = print(buffered);
  return out;
}

}  // namespace boxgen::generator
