// Emission strategies by name, the shape of the code written for one orbit, and every strategy's
// expression graph evaluated in exact rationals against the reference polynomial and its exact
// derivatives. The rounded numbers in the code are checked where they are compiled and run:
// tests/emitted/emitted_accuracy_test.cpp.
#include "generator/codegen/strategies/polynomial_code.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <regex>

#include "generator/codegen/ir/expr.h"
#include "generator/codegen/targets/target_printer.h"
#include "generator/error.h"
#include "tests/generator/derivation_fixture.h"

namespace boxgen::generator {
namespace {

// Orbit 0's code as the C++ printer writes it.
std::string cpp_text(const OrbitCode& code) { return CppPrinter().orbit_functions(code, 0); }

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
    EXPECT_NE(cpp_text(*code).find("orbit_0"), std::string::npos) << cpp_text(*code);
    EXPECT_GT(code->value.total(), 0);
    EXPECT_GE(code->gradient.total(), code->value.total());
    EXPECT_GE(code->hessian.total(), code->gradient.total());
  }
  EXPECT_NE(cpp_text(*horner), cpp_text(*monomial));
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
  EXPECT_NE(cpp_text(*shifted).find("origin o = (1,1,0)"), std::string::npos);
  EXPECT_NE(cpp_text(*shifted).find("const T y0 = x[0] - T(1);"), std::string::npos)
      << cpp_text(*shifted);
  EXPECT_NE(cpp_text(*shifted).find("const T y1 = x[1] - T(1);"), std::string::npos);
  EXPECT_EQ(cpp_text(*shifted).find("const T y2"), std::string::npos);  // o_2 = 0: x[2] itself
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
  // Degree 4 in 3-D: 35 BB-coefficients, de Casteljau levels of 20, 10, 4 and 1 values; those
  // used once are written inline (the schedule, generator/codegen/ir/expr_schedule.h), so the names
  // that appear are the shared ones.
  EXPECT_NE(cpp_text(*bb).find("const T b1 ="), std::string::npos);
  EXPECT_NE(cpp_text(*bb).find("const T q1_1 ="), std::string::npos);
  // The last level is the value; level 3 also feeds the gradient, level 2 the Hessian.
  EXPECT_NE(cpp_text(*bb).find("const T q3_3 ="), std::string::npos);
  EXPECT_NE(cpp_text(*bb).find("const T q2_9 ="), std::string::npos);
  EXPECT_NE(cpp_text(*bb).find("const T value = "), std::string::npos);
  // Barycentric coordinates that are a coordinate itself are no temporaries (l3 = x[2]); l0 =
  // 1 - x[0] is kept as its negation x[0] - 1, subtracted where it is used.
  EXPECT_NE(cpp_text(*bb).find("const T l1 = x[0] - x[1];"), std::string::npos) << cpp_text(*bb);
  EXPECT_EQ(cpp_text(*bb).find("const T l3 ="), std::string::npos) << cpp_text(*bb);
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

// Every strategy's graph, evaluated exactly at random rational points and stencil values, is
// sum_k v_k p_k(x) and its exact gradient and Hessian: the graph computes the reference
// polynomial, whatever the simplifier, the sharing and the schedule made of it.
void check_exact(const std::string& preset) {
  const Derivation& a = fixture::derivation_of(preset);
  const int n = a.spec.dimension();
  std::mt19937_64 rng(7);
  auto rational = [&] {
    return Rational(static_cast<long>(rng() % 2001) - 1000) /
           Rational(static_cast<long>(rng() % 97 + 1));
  };
  int checked = 0;
  for (std::size_t o = 0; o < a.structure.references.size(); ++o) {
    const ReferenceRegion& ref = a.structure.references[o];
    for (auto s :
         {EmissionStrategy::Horner, EmissionStrategy::Separable, EmissionStrategy::Monomial,
          EmissionStrategy::Shifted, EmissionStrategy::Bernstein}) {
      const auto code = orbit_code(ref, static_cast<int>(o), n, a.properties.degree, s);
      if (!code) continue;
      ++checked;
      const generator::Program& p = *code->program;
      for (int trial = 0; trial < 3; ++trial) {
        RatVec x(n), v(ref.basis.size());
        for (auto& xi : x) xi = rational();
        for (auto& vk : v) vk = rational();
        const auto values = generator::evaluate_exactly(p.graph, x, v);
        // Expected: value, then d[] in the order of the outputs (gradient, Hessian row by row).
        std::vector<Rational> expected(1 + n + n * (n + 1) / 2, 0);
        for (std::size_t k = 0; k < ref.basis.size(); ++k) {
          std::size_t at = 0;
          expected[at++] = expected[0] + v[k] * ref.basis[k].eval(x);
          for (int i = 0; i < n; ++i, ++at)
            expected[at] = expected[at] + v[k] * ref.basis[k].derivative(i).eval(x);
          for (int i = 0; i < n; ++i)
            for (int j = i; j < n; ++j, ++at)
              expected[at] = expected[at] + v[k] * ref.basis[k].derivative(i).derivative(j).eval(x);
        }
        EXPECT_EQ(values[p.blocks[0].outputs.at(0).second], expected[0])
            << preset << " " << strategy_name(s);
        for (int b = 1; b < 3; ++b)
          for (const auto& [index, node] : p.blocks[b].outputs)
            EXPECT_EQ(values[node], expected[1 + index])
                << preset << " " << strategy_name(s) << " d[" << index << "]";
      }
    }
  }
  EXPECT_GE(checked, 3) << preset;
}

TEST(PolynomialCode, GraphsAreExactOnZp) { check_exact("zp"); }
TEST(PolynomialCode, GraphsAreExactOnM7) { check_exact("m7"); }
TEST(PolynomialCode, GraphsAreExactOnFcc6) { check_exact("fcc6"); }
TEST(PolynomialCode, GraphsAreExactOnTricubic) { check_exact("tricubic"); }

// Sharing between the value, the gradient and the Hessian (the derivatives differentiate the
// Horner form) makes M7's and M8's value + gradient + Hessian at least 15% cheaper than the 536
// and 895 operations of the unshared code they replace; the value path is never dearer.
TEST(PolynomialCode, DerivativesShareTheValuesHornerForm) {
  const std::pair<const char*, std::array<long, 3>> before[] = {{"m7", {278, 404, 536}},
                                                                {"m8", {415, 628, 895}}};
  for (const auto& [preset, counts] : before) {
    const Derivation& a = fixture::derivation_of(preset);
    const OrbitCode c = choose_orbit_code(a.structure.references[0], 0, 3, a.properties.degree,
                                          EmissionStrategy::Auto);
    EXPECT_LE(c.value.total(), counts[0]) << preset;
    EXPECT_LE(c.gradient.total(), counts[1]) << preset;
    EXPECT_LE(c.hessian.total() * 100, counts[2] * 85) << preset;
  }
}

}  // namespace
}  // namespace boxgen::generator
