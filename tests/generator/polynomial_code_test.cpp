// Emission strategies by name, and the shape of the code written for one orbit. The numbers in
// the code are checked where they are compiled and run: tests/emitted/emitted_accuracy_test.cpp.
#include "generator/polynomial_code.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <regex>

#include "generator/error.h"
#include "tests/generator/derivation_fixture.h"

namespace boxgen::generator {
namespace {

TEST(PolynomialCode, StrategiesByName) {
  EXPECT_EQ(parse_strategy("horner"), EmissionStrategy::Horner);
  EXPECT_EQ(parse_strategy("monomial"), EmissionStrategy::Monomial);
  EXPECT_STREQ(strategy_name(EmissionStrategy::Horner), "horner");
  EXPECT_STREQ(strategy_name(EmissionStrategy::Monomial), "monomial");
  EXPECT_EQ(parse_strategy("separable"), EmissionStrategy::Separable);
  EXPECT_EQ(parse_strategy("auto"), EmissionStrategy::Auto);
  EXPECT_EQ(parse_strategy("shifted"), EmissionStrategy::Shifted);
  EXPECT_EQ(parse_strategy("bernstein"), EmissionStrategy::Bernstein);
  EXPECT_STREQ(strategy_name(EmissionStrategy::Shifted), "shifted");
  EXPECT_STREQ(strategy_name(EmissionStrategy::Bernstein), "bernstein");
  EXPECT_THROW(parse_strategy("knot-planes"), InputError);
}

TEST(PolynomialCode, OneFunctionPerOrbitInEachStrategy) {
  const Derivation& a = fixture::derivation_of("zp");
  const ReferenceRegion& ref = a.structure.references[0];
  const auto horner = orbit_code(ref, 0, 2, 2, EmissionStrategy::Horner);
  const auto monomial = orbit_code(ref, 0, 2, 2, EmissionStrategy::Monomial);
  ASSERT_TRUE(horner && monomial);
  for (const OrbitCode* code : {&*horner, &*monomial}) {
    EXPECT_NE(code->text.find("orbit_0"), std::string::npos) << code->text;
    EXPECT_GT(code->value.total(), 0);
    EXPECT_GE(code->gradient.total(), code->value.total());
    EXPECT_GE(code->hessian.total(), code->gradient.total());
  }
  EXPECT_NE(horner->text, monomial->text);
  // The zp spline is not a tensor product: separable code does not apply, and auto picks the
  // cheaper of the others.
  EXPECT_FALSE(orbit_code(ref, 0, 2, 2, EmissionStrategy::Separable).has_value());
  const OrbitCode chosen = choose_orbit_code(ref, 0, 2, 2, EmissionStrategy::Auto);
  EXPECT_LE(chosen.gradient.total(),
            std::min(horner->gradient.total(), monomial->gradient.total()));
}

// The shifted form names its origin, a point of the reference region other than 0 that the
// generator chose by its own count: here M8's, the midpoint of two vertices, since the vertex at 0
// is the Horner form itself. Its code uses y = x - o and no other coordinates.
TEST(PolynomialCode, ShiftedFormRecordsItsOriginAndWritesY) {
  const Derivation& a = fixture::derivation_of("m8");
  const ReferenceRegion& ref = a.structure.references[0];
  const auto shifted = orbit_code(ref, 0, 3, a.properties.degree, EmissionStrategy::Shifted);
  ASSERT_TRUE(shifted);
  EXPECT_EQ(shifted->form, "about (1,1,0)");
  EXPECT_NE(shifted->text.find("origin o = (1,1,0)"), std::string::npos);
  EXPECT_NE(shifted->text.find("const T y0 = x[0] - T(1);"), std::string::npos) << shifted->text;
  EXPECT_NE(shifted->text.find("const T y1 = x[1] - T(1);"), std::string::npos);
  EXPECT_EQ(shifted->text.find("const T y2"), std::string::npos);  // o_2 = 0: x[2] itself
  // Horner about M8's corner costs more, so auto takes the shifted form (ties would keep Horner).
  const auto horner = orbit_code(ref, 0, 3, a.properties.degree, EmissionStrategy::Horner);
  EXPECT_LT(shifted->gradient.total(), horner->gradient.total());
  EXPECT_EQ(choose_orbit_code(ref, 0, 3, a.properties.degree, EmissionStrategy::Auto).strategy,
            EmissionStrategy::Shifted);
}

// Bernstein-Bezier code exists on simplices only: M7's tetrahedron and zp's triangle, not the
// cubes of M12; asking for it there is an input error naming the region.
TEST(PolynomialCode, BernsteinOnSimplicesOnly) {
  const Derivation& m7 = fixture::derivation_of("m7");
  const auto bb = orbit_code(m7.structure.references[0], 0, 3, 4, EmissionStrategy::Bernstein);
  ASSERT_TRUE(bb);
  // Degree 4 in 3-D: 35 BB-coefficients, de Casteljau levels of 20, 10, 4 and 1 values.
  EXPECT_NE(bb->text.find("const T b34 ="), std::string::npos);
  EXPECT_NE(bb->text.find("const T q1_19 ="), std::string::npos);
  EXPECT_NE(bb->text.find("const T q4_0 ="), std::string::npos);
  EXPECT_NE(bb->text.find("const T l3 = x[2];"), std::string::npos) << bb->text;
  const Derivation& zp = fixture::derivation_of("zp");
  EXPECT_TRUE(orbit_code(zp.structure.references[0], 0, 2, 2, EmissionStrategy::Bernstein));
  const Derivation& m12 = fixture::derivation_of("m12");
  const ReferenceRegion& cube = m12.structure.references[0];
  EXPECT_FALSE(orbit_code(cube, 0, 3, m12.properties.degree, EmissionStrategy::Bernstein));
  try {
    choose_orbit_code(cube, 0, 3, m12.properties.degree, EmissionStrategy::Bernstein);
    ADD_FAILURE() << "bernstein on a cube";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not a simplex"), std::string::npos) << e.what();
  }
}

// auto weighs every applicable strategy by the value + gradient count, reports them all, and
// takes the cheapest; on fcc6 the two orbits each get their own origin.
TEST(PolynomialCode, AutoConsidersEveryApplicableStrategy) {
  const Derivation& a = fixture::derivation_of("fcc6");
  for (std::size_t o = 0; o < a.structure.references.size(); ++o) {
    const ReferenceRegion& ref = a.structure.references[o];
    const OrbitCode chosen =
        choose_orbit_code(ref, static_cast<int>(o), 3, a.properties.degree, EmissionStrategy::Auto);
    std::vector<EmissionStrategy> names;
    for (const auto& c : chosen.considered) {
      names.push_back(c.strategy);
      EXPECT_LE(chosen.gradient.total(), c.gradient.total());
      const auto alone = orbit_code(ref, static_cast<int>(o), 3, a.properties.degree, c.strategy);
      ASSERT_TRUE(alone);
      EXPECT_EQ(alone->gradient.total(), c.gradient.total());
    }
    // Tetrahedra: everything but the separable form applies.
    EXPECT_EQ(names, (std::vector<EmissionStrategy>{
                         EmissionStrategy::Horner, EmissionStrategy::Monomial,
                         EmissionStrategy::Shifted, EmissionStrategy::Bernstein}));
    EXPECT_TRUE(std::regex_search(considered_text(chosen.considered),
                                  std::regex("^horner [0-9]+ / [0-9]+ / [0-9]+, monomial")));
  }
}

}  // namespace
}  // namespace boxgen::generator
