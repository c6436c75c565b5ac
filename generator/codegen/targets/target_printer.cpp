#include "generator/codegen/targets/target_printer.h"

#include <fmt/args.h>
#include <fmt/format.h>

#include "generator/codegen/code_text.h"
#include "generator/codegen/targets/expr_print.h"
#include "generator/embedded_templates.h"

namespace boxgen::generator {

using code::brace_list;
using code::join;
using code::list;

std::string TargetPrinter::functions(const std::vector<OrbitCode>& orbits) const {
  std::vector<std::string> out;
  for (std::size_t o = 0; o < orbits.size(); ++o)
    out.push_back(orbit_functions(orbits[o], static_cast<int>(o)));
  return join(out, "\n");
}

std::string TargetPrinter::dispatch(std::size_t orbit_count) const {
  std::vector<std::string> out;
  for (std::size_t o = 0; o < orbit_count; ++o) out.push_back(orbit_dispatch(static_cast<int>(o)));
  return join(out, "\n");
}

// ---- C++ ----

std::string orbit_comment(const OrbitCode& code) {
  fmt::dynamic_format_arg_store<fmt::format_context> args;
  for (const auto& [name, value] : code.comment.args) args.push_back(fmt::arg(name, value));
  std::string text = fmt::vformat(code.comment.format, args);
  if (!text.empty() && text.back() == '\n') text.pop_back();
  return text;
}

std::string CppPrinter::literal(const Rational& r) const {
  return fmt::format("T({})", table_literal(r));
}

std::string CppPrinter::table_literal(const Rational& r) {
  return fmt::format("{:.17g}", to_double(r));
}

std::string CppPrinter::declaration() const { return "const T "; }

std::string CppPrinter::qualifiers() const { return ""; }

std::string CppPrinter::orbit_functions(const OrbitCode& code, int orbit) const {
  return fmt::format(fmt::runtime(templates::orbit_function),
                     fmt::arg("comment", orbit_comment(code)), fmt::arg("qualifiers", qualifiers()),
                     fmt::arg("orbit", orbit),
                     fmt::arg("body", print_cpp_body(*code.program, *this)));
}

std::string CppPrinter::orbit_dispatch(int orbit) const {
  return fmt::format("      case {0}: return detail::orbit_{0}<Order>(v, x, d);", orbit);
}

TemplateFields CppPrinter::table_fields(const Derivation& a, const KnotPlaneKeys& knot_keys,
                                        const IntColumns& hermite, const CellTables& t) {
  const SplineStructure& s = a.structure;
  const int n = a.spec.dimension();
  KnotPlaneKeys keys = knot_keys;
  std::vector<std::string> lookup_rows, normal_rows, orbit_sizes;
  for (const auto& row : t.lookup) lookup_rows.push_back(brace_list(row));
  for (const auto& nu : keys.planes) normal_rows.push_back(brace_list(nu));
  normal_rows.push_back(brace_list(IntVec(n, 0)));  // a zero row keeps the arrays non-empty
  keys.mins.push_back(0);
  keys.widths.push_back(1);
  for (const auto& r : s.references) orbit_sizes.push_back(std::to_string(r.stencil.size()));
  // Per cell its row of Traits::kCells ({cube, orbit, {keys}, {perm}, {sign}, {a}}) and its
  // stencil offsets, padded with zero points to the largest stencil.
  std::vector<std::string> cells, offsets;
  for (std::size_t c = 0; c < t.cube.size(); ++c) {
    cells.push_back(fmt::format("{{{}, {}, {}, {}, {}, {}}}", t.cube[c], t.orbit[c],
                                brace_list(t.keys[c]), brace_list(t.perm[c]), brace_list(t.sign[c]),
                                brace_list(t.a[c])));
    std::vector<std::string> points;
    for (const IntVec& d : t.offset[c]) points.push_back(brace_list(d));
    points.resize(static_cast<std::size_t>(s.stencil_max), brace_list(IntVec(n, 0)));
    offsets.push_back("{" + join(points) + "}");
  }
  std::vector<std::string> centre, hermite_rows;
  for (const auto& c : s.centre) centre.push_back(table_literal(c));
  for (const auto& col : hermite) hermite_rows.push_back(brace_list(col));
  return {{"centre", join(centre)},
          {"reach_lo", list(t.reach_lo)},
          {"reach_hi", list(t.reach_hi)},
          {"hermite", join(hermite_rows)},
          {"scale", std::to_string(s.scale)},
          {"cube_count", std::to_string(t.lookup.size())},
          {"normal_count", std::to_string(keys.planes.size())},
          {"normals", join(normal_rows)},
          {"normal_min", list(keys.mins)},
          {"normal_width", list(keys.widths)},
          {"normal_stride", list(keys.strides)},
          {"lookup_size", std::to_string(keys.size())},
          {"lookup", join(lookup_rows, ",\n      ")},
          {"cell_count", std::to_string(cells.size())},
          {"cells", join(cells, ",\n      ")},
          {"orbit_count", std::to_string(s.references.size())},
          {"orbit_stencil_sizes", join(orbit_sizes)},
          {"offsets", join(offsets, ",\n      ")}};
}

// ---- CUDA ----

std::string CudaPrinter::qualifiers() const { return "BOXGEN_HOST_DEVICE "; }

std::string CudaPrinter::orbit_dispatch(int orbit) const {
  return fmt::format("    case {0}: return orbit_{0}<Order>(v, x, d);", orbit);
}

// ---- GLSL ----

namespace {

// The shortest decimal of 9 (float) or 17 (double) significant digits, always with a '.' or an
// exponent (GLSL reads "3" as an int).
std::string decimal(double value, int digits) {
  std::string text = fmt::format("{:.{}g}", value, digits);
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

template <class Rows>
std::string list_rows(const Rows& rows) {
  std::vector<std::string> parts;
  for (const auto& row : rows) parts.push_back(list(row));
  return join(parts, ",\n    ");
}

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

}  // namespace

GlslPrinter::GlslPrinter(std::string name, int dimension, int stencil_size, bool double_precision)
    : name_(std::move(name)),
      dimension_(dimension),
      stencil_size_(stencil_size),
      double_precision_(double_precision) {}

std::string GlslPrinter::literal(const Rational& r) const {
  if (double_precision_) return decimal(to_double(r), 17) + "LF";
  return decimal(static_cast<double>(static_cast<float>(to_double(r))), 9);
}

std::string GlslPrinter::declaration() const { return double_precision_ ? "double " : "float "; }

std::string GlslPrinter::orbit_functions(const OrbitCode& code, int orbit) const {
  const std::string real = double_precision_ ? "double" : "float";
  const int derivatives = dimension_ + dimension_ * (dimension_ + 1) / 2;
  std::string text = orbit_comment(code) + "\n";
  for (int order = 0; order <= 2; ++order)
    text += fmt::format(
        "{0} {1}_orbit{2}_{3}(in {0} v[{4}], in {0} x[{5}], inout {0} d[{6}]) {{\n"
        "{7}}}\n",
        real, name_, orbit, order, stencil_size_, dimension_, derivatives,
        print_straight_line(*code.program, order, *this, "  "));
  return text;
}

std::string GlslPrinter::orbit_dispatch(int orbit) const {
  std::vector<std::string> lines;
  for (int order = 0; order <= 2; ++order)
    lines.push_back(fmt::format("  if (order == {0} && o == {1}) return {2}_orbit{1}_{0}(v, x, d);",
                                order, orbit, name_));
  return join(lines, "\n");
}

GlslPrinter::Tables GlslPrinter::tables(const SplineStructure& s, const KnotPlaneKeys& keys,
                                        const CellTables& t) const {
  const int n = dimension_;
  const std::size_t orbits = s.references.size();
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
  // The tables indexed by the point's cell, and with several orbits by its orbit.
  const std::size_t cells = t.cube.size();
  const bool orbit_indexed = orbits > 1;
  const std::string& name = name_;
  const std::vector<IntTable> tables{
      {"table_lookup", name + "_kLookup", fmt::format("{} * {}", t.lookup.size(), keys.size()),
       list_rows(t.lookup), flat_ints(t.lookup), true},
      {"table_cell_cube", name + "_kCellCube", std::to_string(cells), list(t.cube), t.cube, true},
      {"table_cell_orbit", name + "_kCellOrbit", std::to_string(cells), list(t.orbit), t.orbit,
       true},
      {"table_cell_keys", name + "_kCellKeys",
       fmt::format("{} * ({} + 1)", cells, keys.planes.size()), list_rows(t.keys),
       flat_ints(t.keys), true},
      {"table_cell_perm", name + "_kCellPerm", fmt::format("{} * {}", cells, n), list_rows(t.perm),
       flat_ints(t.perm), true},
      {"table_cell_sign", name + "_kCellSign", fmt::format("{} * {}", cells, n), list_rows(t.sign),
       flat_ints(t.sign), true},
      {"table_cell_a", name + "_kCellA", fmt::format("{} * {}", cells, n), list_rows(t.a),
       flat_ints(t.a), true},
      {"table_orbit_stencil_size", name + "_kOrbitStencilSize", std::to_string(orbits), list(sizes),
       sizes, orbit_indexed},
      {"table_reference_stencil", name + "_kReferenceStencil",
       fmt::format("{} * {} * {}", orbits, s.stencil_max, n), list_rows(reference_stencil),
       flat_ints(reference_stencil), orbit_indexed}};
  // In `constant`, each a `const` array; in `buffered`, the run-time-indexed ones members of one
  // read-only storage block at the place of the first (the others' lines left empty).
  Tables out;
  std::string members;
  for (const IntTable& table : tables)
    if (table.run_time_indexed)
      members += fmt::format("  int {}[{}];\n", table.name, table.values.size());
  bool first = true;
  for (const IntTable& table : tables) {
    const std::string declaration =
        fmt::format("const int {}[{}] = int[]({});", table.name, table.size, table.text);
    out.constant.emplace_back(table.field, declaration);
    if (!table.run_time_indexed) {
      out.buffered.emplace_back(table.field, declaration);
      continue;
    }
    out.buffered.emplace_back(
        table.field, first ? fmt::format("layout(std430, binding = BOXGEN_TABLES_BINDING) readonly "
                                         "buffer {}_Tables {{\n{}}};",
                                         name, members)
                           : std::string());
    out.block.insert(out.block.end(), table.values.begin(), table.values.end());
    first = false;
  }
  return out;
}

}  // namespace boxgen::generator
