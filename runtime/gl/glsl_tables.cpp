#include "runtime/gl/glsl_tables.h"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <utility>

#include "runtime/gl/gl_context.h"

namespace boxgen::runtime::gl {

namespace {

// The tables the emitted evaluator indexes by the point's cell (templates/evaluator.glsl.fmt).
constexpr const char* kCellTables[] = {"kLookup",   "kCellCube", "kCellOrbit", "kCellKeys",
                                       "kCellPerm", "kCellSign", "kCellA"};

// One `const int NAME[SIZE] = int[](...);` declaration of the text: where it is and its entries.
struct Table {
  std::string name;
  std::size_t begin = 0, end = 0;
  std::vector<int> values;
};

Table find_table(const std::string& text, const std::string& name) {
  const std::string head = "const int " + name + "[";
  std::size_t at = text.find(head);
  while (at != std::string::npos && at != 0 && text[at - 1] != '\n') at = text.find(head, at + 1);
  const std::string open = "] = int[](";
  const std::size_t values = at == std::string::npos ? at : text.find(open, at);
  const std::size_t close = values == std::string::npos ? values : text.find(");", values);
  if (close == std::string::npos)
    throw GlError(
        fmt::format("the GLSL evaluator has no table {} (not an emitted evaluator)", name));
  Table t{name, at, close + 2, {}};
  const char* p = text.c_str() + values + open.size();
  const char* const stop = text.c_str() + close;
  while (p < stop) {
    char* next = nullptr;
    errno = 0;
    const long v = std::strtol(p, &next, 10);
    if (next == p || errno != 0 || v < -(1L << 30) || v > (1L << 30))
      throw GlError(fmt::format("the GLSL table {} has an entry that is not an int", name));
    t.values.push_back(static_cast<int>(v));
    p = next;
    while (p < stop && (*p == ',' || *p == ' ' || *p == '\n')) ++p;
  }
  if (t.values.empty()) throw GlError(fmt::format("the GLSL table {} is empty", name));
  return t;
}

}  // namespace

BufferedTables tables_in_buffer(const std::string& text, const std::string& name, int binding) {
  std::vector<Table> tables;
  for (const char* t : kCellTables) tables.push_back(find_table(text, name + "_" + t));
  // The tables indexed by the cell's orbit: at run time only where there are several orbits.
  Table orbit_sizes = find_table(text, name + "_kOrbitStencilSize");
  if (orbit_sizes.values.size() > 1) {
    tables.push_back(std::move(orbit_sizes));
    tables.push_back(find_table(text, name + "_kReferenceStencil"));
  }
  std::sort(tables.begin(), tables.end(),
            [](const Table& a, const Table& b) { return a.begin < b.begin; });
  // The block takes the place of the first table; the others' declarations go.
  std::string block =
      fmt::format("layout(std430, binding = {}) readonly buffer {}_Tables {{\n", binding, name);
  BufferedTables out;
  for (const Table& t : tables) {
    block += fmt::format("  int {}[{}];\n", t.name, t.values.size());
    out.block.insert(out.block.end(), t.values.begin(), t.values.end());
  }
  block += "};";
  std::size_t from = 0;
  for (const Table& t : tables) {
    out.text.append(text, from, t.begin - from);
    if (&t == &tables.front()) out.text += block;
    from = t.end;
  }
  out.text.append(text, from, std::string::npos);
  return out;
}

}  // namespace boxgen::runtime::gl
