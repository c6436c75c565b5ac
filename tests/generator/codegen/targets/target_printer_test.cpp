// The printers per target (generator/codegen/targets/target_printer.h): what each owns, literals,
// declarations, the orbit functions and their dispatch, and the tables printed from the numbers of
// generator/codegen/targets/evaluator_tables.h. The printed files are compared byte for byte with
// generated/ (GeneratedHeadersAreFresh) and evaluated where they run (tests/emitted, tests/gpu).
#include "generator/codegen/targets/target_printer.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "generator/codegen/targets/expr_print.h"
#include "generator/rational.h"
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
  EXPECT_NE(cpp_text.find(orbit_comment(orbits[1])), std::string::npos);  // each with its comment
  EXPECT_EQ(orbit_comment(orbits[1]).rfind("// Orbit 1: the spline on the reference region", 0),
            0u);
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

namespace boxgen::generator {
namespace {

// docs/extending.md, "A target language", step 1, followed once: a printer for Python with exact
// fractions, a subclass of TargetPrinter and nothing else. The print pass writes statements that
// Python reads as they are ("t0 = x[0] - Fraction('1');", "return t0 * v[2];").
class PythonPrinter : public TargetPrinter {
 public:
  std::string literal(const Rational& r) const override {
    return "Fraction('" + to_string(r) + "')";
  }
  std::string declaration() const override { return ""; }
  std::string orbit_functions(const OrbitCode& code, int orbit) const override {
    return fmt::format("def orbit_{}(v, x, d):\n{}", orbit,
                       print_straight_line(*code.program, 2, *this, "  "));
  }
  std::string orbit_dispatch(int orbit) const override {
    return fmt::format("  if o == {0}:\n    return orbit_{0}(v, x, d)", orbit);
  }
};

// The new target's code, run by Debian's python3, equals sum_k v_k p_k(x) and its exact
// derivatives at rational points (expected from the basis polynomials, as polynomial_code_test
// does), for both orbits of fcc6.
TEST(TargetPrinter, ANewTargetFollowingTheRecipePrintsExactCode) {
  const Derivation& a = fixture::derivation_of("fcc6");
  const int n = 3, outputs = 1 + n + n * (n + 1) / 2;
  std::vector<OrbitCode> orbits;
  for (std::size_t o = 0; o < a.structure.references.size(); ++o)
    orbits.push_back(choose_orbit_code(a.structure.references[o], static_cast<int>(o), n,
                                       a.properties.degree, EmissionStrategy::Auto));
  const PythonPrinter python;
  std::string script = "from fractions import Fraction\n\n" + python.functions(orbits) +
                       "\ndef orbit(o, v, x, d):\n" + python.dispatch(orbits.size()) + "\n\n";
  std::vector<std::vector<Rational>> expected;
  for (std::size_t o = 0; o < orbits.size(); ++o) {
    const ReferenceRegion& ref = a.structure.references[o];
    for (int trial = 0; trial < 2; ++trial) {
      RatVec x(n), v(ref.basis.size());
      std::vector<std::string> xs, vs;
      for (int i = 0; i < n; ++i) {
        x[i] = fraction(trial + i + 1, 7 + static_cast<long>(o));
        xs.push_back("Fraction('" + to_string(x[i]) + "')");
      }
      for (std::size_t k = 0; k < v.size(); ++k) {
        v[k] = fraction(static_cast<long>(k * k) - 5, 3 + trial);
        vs.push_back("Fraction('" + to_string(v[k]) + "')");
      }
      std::vector<Rational> e(outputs, 0);
      for (std::size_t k = 0; k < ref.basis.size(); ++k) {
        std::size_t at = 0;
        e[at] = e[at] + v[k] * ref.basis[k].eval(x);
        ++at;
        for (int i = 0; i < n; ++i, ++at) e[at] = e[at] + v[k] * ref.basis[k].derivative(i).eval(x);
        for (int i = 0; i < n; ++i)
          for (int j = i; j < n; ++j, ++at)
            e[at] = e[at] + v[k] * ref.basis[k].derivative(i).derivative(j).eval(x);
      }
      expected.push_back(e);
      script += fmt::format(
          "d = [Fraction(0)] * {0}\nvalue = orbit({1}, [{2}], [{3}], d)\n"
          "print(' '.join(str(r) for r in [value] + d))\n",
          outputs - 1, o, fmt::join(vs, ", "), fmt::join(xs, ", "));
    }
  }
  const std::string dir = ::testing::TempDir();
  const std::string source = dir + "/boxgen_python_target.py", out = dir + "/boxgen_python_out";
  std::ofstream(source) << script;
  ASSERT_EQ(std::system(("/usr/bin/python3 " + source + " > " + out).c_str()), 0) << script;
  std::ifstream in(out);
  for (const auto& e : expected) {
    std::string line;
    ASSERT_TRUE(std::getline(in, line)) << script;
    std::istringstream words(line);
    std::vector<Rational> got;
    for (std::string w; words >> w;) got.push_back(parse_rational(w));
    EXPECT_EQ(got, e) << line;
  }
  std::remove(source.c_str());
  std::remove(out.c_str());
}

}  // namespace
}  // namespace boxgen::generator
