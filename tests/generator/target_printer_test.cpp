// The printers per target (generator/target_printer.h): what each owns, literals, declarations,
// the orbit functions and their dispatch, and the tables printed from the numbers of
// generator/evaluator_tables.h. The printed files are compared byte for byte with generated/
// (GeneratedHeadersAreFresh) and evaluated where they run (tests/emitted, tests/gpu).
#include "generator/target_printer.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>

#include "tests/generator/derivation_fixture.h"

namespace boxgen::generator {
namespace {

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(TargetPrinter, LiteralsAndDeclarationsPerTarget) {
  const Rational third = fraction(1, 3), three(3);
  const CppPrinter cpp;
  const CudaPrinter cuda;
  const GlslPrinter glsl("f", 3, 4, false), glsl_double("f", 3, 4, true);
  EXPECT_EQ(cpp.literal(third), "T(0.33333333333333331)");
  EXPECT_EQ(CppPrinter::table_literal(third), "0.33333333333333331");
  EXPECT_EQ(cuda.literal(third), cpp.literal(third));
  EXPECT_EQ(glsl.literal(third), "0.333333343");  // the float nearest 1/3, 9 digits
  EXPECT_EQ(glsl_double.literal(third), "0.33333333333333331LF");
  EXPECT_EQ(glsl.literal(three), "3.0");  // GLSL reads "3" as an int
  EXPECT_EQ(cpp.declaration(), "const T ");
  EXPECT_EQ(glsl.declaration(), "float ");
  EXPECT_EQ(glsl_double.declaration(), "double ");
}

TEST(TargetPrinter, OrbitFunctionsAndDispatchPerTarget) {
  const Derivation& fcc6 = fixture::derivation_of("fcc6");  // two orbits
  std::vector<OrbitCode> orbits;
  for (std::size_t o = 0; o < fcc6.structure.references.size(); ++o)
    orbits.push_back(choose_orbit_code(fcc6.structure.references[o], static_cast<int>(o), 3,
                                       fcc6.properties.degree, EmissionStrategy::Auto));
  ASSERT_EQ(orbits.size(), 2u);
  const CppPrinter cpp;
  const CudaPrinter cuda;
  const GlslPrinter glsl("fcc6", 3, fcc6.structure.stencil_max, false);

  const std::string cpp_text = cpp.functions(orbits);
  EXPECT_EQ(count(cpp_text, "template <int Order, class T>\nT orbit_"), 2u) << cpp_text;
  EXPECT_NE(cpp_text.find(orbits[1].comment), std::string::npos);  // each with its comment
  const std::string cuda_text = cuda.functions(orbits);
  EXPECT_EQ(count(cuda_text, "template <int Order, class T>\nBOXGEN_HOST_DEVICE T orbit_"), 2u);
  // CUDA's code is C++'s with the qualifier: nothing else differs.
  std::string unqualified = cuda_text;
  for (std::size_t at; (at = unqualified.find("BOXGEN_HOST_DEVICE ")) != std::string::npos;)
    unqualified.erase(at, 19);
  EXPECT_EQ(unqualified, cpp_text);
  EXPECT_EQ(cpp.dispatch(2),
            "      case 0: return detail::orbit_0<Order>(v, x, d);\n"
            "      case 1: return detail::orbit_1<Order>(v, x, d);");
  EXPECT_EQ(cuda.dispatch(1), "    case 0: return orbit_0<Order>(v, x, d);");

  const std::string glsl_text = glsl.functions(orbits);
  for (const char* f : {"float fcc6_orbit0_0(in float v[", "float fcc6_orbit0_2(",
                        "float fcc6_orbit1_1(", "float fcc6_orbit1_2("})
    EXPECT_NE(glsl_text.find(f), std::string::npos) << f;
  EXPECT_EQ(count(glsl.dispatch(2), "if (order == "), 6u);  // per orbit and path
  EXPECT_NE(glsl.dispatch(2).find("if (order == 2 && o == 1) return fcc6_orbit1_2(v, x, d);"),
            std::string::npos);
}

TEST(TargetPrinter, TablesArePrintedFromTheNumbers) {
  const Derivation& m7 = fixture::derivation_of("m7");
  const KnotPlaneKeys keys = knot_plane_keys(m7);
  const IntColumns hermite = hermite_basis(m7);
  const CellTables t = cell_tables(m7, keys, hermite);
  std::map<std::string, std::string> cpp;
  for (const auto& [field, text] : CppPrinter::table_fields(m7, keys, hermite, t))
    cpp.emplace(field, text);
  EXPECT_EQ(cpp.at("cell_count"), std::to_string(t.cube.size()));
  EXPECT_EQ(count(cpp.at("cells"), "\n") + 1, t.cube.size());  // one cell per line
  // The first cell's row: {cube, orbit, {keys}, {perm}, {sign}, {a}}.
  EXPECT_EQ(cpp.at("cells").rfind(fmt::format("{{{}, {}, {{", t.cube[0], t.orbit[0]), 0), 0u);
  EXPECT_EQ(count(cpp.at("lookup"), "\n") + 1, t.lookup.size());
  // A zero row after the knot normals keeps the arrays non-empty for splines without any.
  EXPECT_EQ(count(cpp.at("normals"), "{"), keys.planes.size() + 1);

  const GlslPrinter glsl("m7", 3, m7.structure.stencil_max, false);
  const GlslPrinter::Tables g = glsl.tables(m7.structure, keys, t);
  ASSERT_EQ(g.constant.size(), g.buffered.size());
  std::size_t entries = 0;
  for (const auto& row : t.lookup) entries += row.size();
  // The block begins with the lookup table, then the cells' cubes.
  ASSERT_GE(g.block.size(), entries + t.cube.size());
  std::vector<int> lookup;
  for (const auto& row : t.lookup) lookup.insert(lookup.end(), row.begin(), row.end());
  EXPECT_TRUE(std::equal(lookup.begin(), lookup.end(), g.block.begin()));
  EXPECT_TRUE(std::equal(t.cube.begin(), t.cube.end(), g.block.begin() + entries));
  EXPECT_EQ(g.constant[0].second.rfind("const int m7_kLookup[", 0), 0u);
  EXPECT_NE(g.buffered[0].second.find("buffer m7_Tables {"), std::string::npos);
}

}  // namespace
}  // namespace boxgen::generator
