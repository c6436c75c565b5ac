// The GLSL printer (generator/codegen/targets/glsl_evaluator.h): the entry points and types of each
// precision and dimension, the application's fetch, one function per orbit and path. Its numbers
// are checked where the shader runs: tests/gpu/glsl_exactness_test.cpp.
#include "generator/codegen/targets/glsl_evaluator.h"

#include <gtest/gtest.h>

#include "tests/generator/derivation_fixture.h"

namespace boxgen::generator {
namespace {

std::vector<OrbitCode> codes(const Derivation& a) {
  std::vector<OrbitCode> out;
  for (std::size_t o = 0; o < a.structure.references.size(); ++o)
    out.push_back(choose_orbit_code(a.structure.references[o], static_cast<int>(o),
                                    a.spec.dimension(), a.properties.degree,
                                    EmissionStrategy::Auto));
  return out;
}

TEST(GlslEvaluator, EntryPointsInEachPrecisionAndDimension) {
  const Derivation& zp = fixture::derivation_of("zp");
  const std::string f = glsl_evaluator(zp, "banner", "zp", codes(zp), {}, false).text;
  // No #version line (the including shader has one); the comments may name it.
  EXPECT_NE(f.rfind("//", 0), std::string::npos);
  EXPECT_EQ(f.find("\n#version"), std::string::npos);
  EXPECT_NE(f.find("float zp_value(vec2 x)"), std::string::npos);
  EXPECT_NE(f.find("float zp_value_gradient(vec2 x, out vec2 g)"), std::string::npos);
  EXPECT_NE(f.find("float zp_value_gradient_hessian(vec2 x, out vec2 g, out mat2 h)"),
            std::string::npos);
  EXPECT_NE(f.find("zp_fetch(origin"), std::string::npos);  // the application's fetch
  for (const char* path : {"zp_orbit0_0(", "zp_orbit0_1(", "zp_orbit0_2("})
    EXPECT_NE(f.find(path), std::string::npos) << path;
  const Derivation& m7 = fixture::derivation_of("m7");
  const std::string d = glsl_evaluator(m7, "banner", "m7", codes(m7), {}, true).text;
  EXPECT_NE(d.find("double m7_value_gradient_hessian(dvec3 x, out dvec3 g, out dmat3 h)"),
            std::string::npos);
  EXPECT_NE(d.find("LF"), std::string::npos);  // double literals
  EXPECT_EQ(d.find("float "), std::string::npos);
}

// The variant with the run-time-indexed tables in a storage block: the block's members are the
// tables the `const` text declares (by name and size), in order, and the block holds their
// entries; with one orbit the orbit tables stay `const`; every other line is the text's.
TEST(GlslEvaluator, TablesInAStorageBlockAsData) {
  for (const char* preset : {"zp", "fcc6"}) {
    const Derivation& a = fixture::derivation_of(preset);
    const std::string name = preset;
    const GlslText g = glsl_evaluator(a, "banner", name, codes(a), {}, false);
    const bool orbits = a.structure.references.size() > 1;
    std::vector<std::string> tables{"kLookup",   "kCellCube", "kCellOrbit", "kCellKeys",
                                    "kCellPerm", "kCellSign", "kCellA"};
    if (orbits) tables.insert(tables.end(), {"kOrbitStencilSize", "kReferenceStencil"});
    std::size_t entries = 0, at = 0;
    for (const std::string& t : tables) {
      const std::string member = "  int " + name + "_" + t + "[";
      at = g.buffered.find(member, at);
      ASSERT_NE(at, std::string::npos) << preset << " " << t;
      entries += std::stoul(g.buffered.substr(at + member.size()));
      EXPECT_EQ(g.buffered.find("const int " + name + "_" + t + "["), std::string::npos) << t;
      EXPECT_NE(g.text.find("const int " + name + "_" + t + "["), std::string::npos) << t;
    }
    EXPECT_EQ(g.block.size(), entries) << preset;
    EXPECT_NE(g.buffered.find("layout(std430, binding = BOXGEN_TABLES_BINDING) readonly buffer " +
                              name + "_Tables {"),
              std::string::npos);
    EXPECT_EQ(g.buffered.find("const int " + name + "_kReferenceStencil[") != std::string::npos,
              !orbits);
    // Outside the tables' declarations the two texts are the same: the same lines in order.
    const auto code_lines = [](const std::string& text) {
      std::vector<std::string> out;
      std::size_t from = 0;
      while (from < text.size()) {
        const std::size_t end = text.find('\n', from);
        const std::string line = text.substr(from, end - from);
        if (line.find("const int") != 0 && line.find("  int ") != 0 && line.find("    ") != 0 &&
            line.find("layout(") != 0 && line != "};" && !line.empty())
          out.push_back(line);
        from = end == std::string::npos ? text.size() : end + 1;
      }
      return out;
    };
    EXPECT_EQ(code_lines(g.text), code_lines(g.buffered)) << preset;
  }
}

}  // namespace
}  // namespace boxgen::generator
