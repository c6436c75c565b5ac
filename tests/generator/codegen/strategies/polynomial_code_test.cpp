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
#include "generator/codegen/targets/emission_report.h"
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
      const expr::Program& p = *code->program;
      for (int trial = 0; trial < 3; ++trial) {
        RatVec x(n), v(ref.basis.size());
        for (auto& xi : x) xi = rational();
        for (auto& vk : v) vk = rational();
        const auto values = expr::evaluate_exactly(p.graph, x, v);
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

}  // namespace
}  // namespace boxgen::generator
