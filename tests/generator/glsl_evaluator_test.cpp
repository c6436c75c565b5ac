// The GLSL printer (generator/glsl_evaluator.h): the entry points and types of each precision and
// dimension, the application's fetch, one function per orbit and path. Its numbers are checked
// where the shader runs: tests/gpu/glsl_exactness_test.cpp.
#include "generator/glsl_evaluator.h"

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
  const std::string f = glsl_evaluator(zp, "banner", "zp", codes(zp), {}, false);
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
  const std::string d = glsl_evaluator(m7, "banner", "m7", codes(m7), {}, true);
  EXPECT_NE(d.find("double m7_value_gradient_hessian(dvec3 x, out dvec3 g, out dmat3 h)"),
            std::string::npos);
  EXPECT_NE(d.find("LF"), std::string::npos);  // double literals
  EXPECT_EQ(d.find("float "), std::string::npos);
}

}  // namespace
}  // namespace boxgen::generator
