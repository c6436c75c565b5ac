#include "generator/glsl_evaluator.h"

#include <fmt/args.h>
#include <fmt/format.h>

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

}  // namespace

std::string glsl_evaluator(const Derivation& a, const std::string& banner, const std::string& name,
                           const std::vector<OrbitCode>& orbits,
                           const std::vector<std::string>& cost_lines, bool double_precision) {
  const int n = a.spec.dimension();
  const int derivatives = n + n * (n + 1) / 2;
  const std::string real = double_precision ? "double" : "float";
  const std::string prefix = double_precision ? "d" : "";
  const Syntax syntax = glsl_syntax(double_precision);
  const SplineStructure& s = a.structure;
  KnotPlaneKeys keys = knot_plane_keys(a);
  const IntColumns hermite = hermite_basis(a);
  const CellTables t = cell_tables(a, keys, hermite);
  std::vector<IntVec> normals = keys.planes;
  normals.push_back(IntVec(n, 0));  // a zero row keeps the arrays non-empty
  keys.mins.push_back(0);
  keys.widths.push_back(1);
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
  std::vector<std::string> gradient, hessian;
  for (int i = 0; i < n; ++i) gradient.push_back(fmt::format("d[{}]", i));
  for (int col = 0; col < n; ++col)
    for (int row = 0; row < n; ++row) {
      const int i = std::min(row, col), j = std::max(row, col);
      hessian.push_back(fmt::format("d[{}]", n + i * n - i * (i - 1) / 2 + (j - i)));
    }
  fmt::dynamic_format_arg_store<fmt::format_context> args;
  auto add = [&](const char* key, const auto& value) { args.push_back(fmt::arg(key, value)); };
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
  add("hermite", flat(hermite_rows));
  add("normal_count", keys.planes.size());
  add("normals", flat_rows(normals));
  add("normal_min", flat(keys.mins));
  add("normal_width", flat(keys.widths));
  add("normal_stride", flat(keys.strides));
  add("cube_count", t.lookup.size());
  add("lookup_size", keys.size());
  add("lookup", flat_rows(t.lookup));
  add("cell_count", t.cube.size());
  add("cell_cube", flat(t.cube));
  add("cell_orbit", flat(t.orbit));
  add("cell_keys", flat_rows(t.keys));
  add("cell_perm", flat_rows(t.perm));
  add("cell_sign", flat_rows(t.sign));
  add("cell_a", flat_rows(t.a));
  add("orbit_count", orbits.size());
  // One orbit: a constant, so that the compiler folds the reference stencil into the code.
  add("orbit_of_cell", orbits.size() == 1 ? std::string("0") : name + "_kCellOrbit[cell]");
  add("orbit_stencil_sizes", flat(sizes));
  add("reference_stencil", flat_rows(reference_stencil));
  add("orbit_functions", join(functions, "\n"));
  add("orbit_dispatch", join(dispatch, "\n"));
  add("gradient_args", join(gradient));
  add("hessian_args", join(hessian));
  std::string select;
  for (int i = 0; i + 1 < n; ++i) select += fmt::format("i == {0} ? x[{0}] : ", i);
  select += fmt::format("x[{}]", n - 1);
  // "if (k == 0) array[0] = value; else if ..." over the `size` entries of the array.
  const auto set_chain = [](const char* array, int size) {
    std::string chain;
    for (int k = 0; k < size; ++k)
      chain += fmt::format("{}  {}if (k == {}) {}[{}] = value;", k ? "\n" : "", k ? "else " : "", k,
                           array, k);
    return chain;
  };
  add("component_select", select);
  add("set_chain", set_chain("d", derivatives));
  add("set_coordinate_chain", set_chain("x", n));
  return fmt::vformat(templates::evaluator_glsl, args);
}

}  // namespace boxgen::generator
