// What the strategies build with: the order of d[], the derivative factors, and the stencil
// values' linear combinations evaluated exactly, with and without shared partial sums.
#include "generator/codegen/strategies/strategy_builders.h"

#include <gtest/gtest.h>

#include <optional>
#include <random>
#include <vector>

#include "generator/codegen/targets/target_printer.h"
#include "tests/generator/derivation_fixture.h"

namespace boxgen::generator::strategies {
namespace {

TEST(StrategyBuilders, DerivativesInTheOrderOfD) {
  const std::vector<Exponent> three = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 0, 0}, {1, 1, 0},
                                       {1, 0, 1}, {0, 2, 0}, {0, 1, 1}, {0, 0, 2}};
  EXPECT_EQ(derivative_indices(3, 2), three);
  EXPECT_EQ(derivative_indices(2, 1), (std::vector<Exponent>{{1, 0, 0}, {0, 1, 0}}));
  EXPECT_TRUE(derivative_indices(3, 0).empty());
}

TEST(StrategyBuilders, DerivativeFactor) {
  Exponent lowered{0, 0, 0};
  // d^2/dx0^2 x0^3 x1 = 6 x0 x1
  EXPECT_EQ(derivative_factor({3, 1, 0}, {2, 0, 0}, lowered), 6);
  EXPECT_EQ(lowered, (Exponent{1, 1, 0}));
  EXPECT_EQ(derivative_factor({1, 0, 2}, {0, 1, 0}, lowered), 0);  // no x1 to differentiate
}

// Rows sharing the ratio of inputs 0 and 1 (2:1 in both) get a partial sum when shared; both
// graphs compute sum_i w_i v_i exactly.
TEST(StrategyBuilders, LinearNodesAreExact) {
  const std::vector<LinearRow> rows = {
      {{0, Rational(2)}, {1, Rational(1)}, {2, Rational(-1) / Rational(3)}},
      {{0, Rational(4)}, {1, Rational(2)}},
      {{2, Rational(5)}}};
  const RatVec v = {Rational(3), Rational(-7) / Rational(2), Rational(11)};
  for (bool shared : {false, true}) {
    Build b;
    std::size_t sums = 99;
    const std::vector<NodeId> nodes = linear_nodes(b, rows, 3, shared, &sums);
    ASSERT_EQ(nodes.size(), rows.size());
    const auto values = evaluate_exactly(b.g, RatVec{}, v);
    for (std::size_t r = 0; r < rows.size(); ++r) {
      Rational expected = 0;
      for (const auto& [i, w] : rows[r]) expected = expected + w * v[i];
      EXPECT_EQ(values[nodes[r]], expected) << "row " << r << (shared ? " shared" : "");
    }
    if (shared)
      EXPECT_GE(sums, 1u);
    else
      EXPECT_EQ(sums, 0u);
  }
}

// docs/extending.md's recipe "An emission strategy", step 2, followed: a strategy that writes
// every stencil polynomial out monomial by monomial, sum_k v_k sum_m c_km x^m, and each
// derivative term by term with derivative_factor, built with these builders and handed to
// `finish`. Its graph is exact and the C++ printer writes it; it is dearer than Horner, which is
// why it is no strategy of the generator.
std::optional<OrbitCode> written_out_code(const ReferenceRegion& ref, int n, int degree) {
  Build b;
  const std::vector<NodeId> x = b.coordinates(n);
  const std::vector<Exponent>& exponents = monomial_exponents(n, degree);
  auto power = [&](const Exponent& e) {
    NodeId m = b.g.constant(1);
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < e[i]; ++k) m = product(b.g, m, x[i]);
    return m;
  };
  // d^D of sum_k v_k p_k, D = 0 for the value.
  auto derivative = [&](const Exponent& d) {
    NodeId acc = b.zero();
    for (std::size_t k = 0; k < ref.basis.size(); ++k) {
      const auto& c = ref.basis[k].coefficients();
      for (std::size_t m = 0; m < c.size(); ++m) {
        Exponent lowered{0, 0, 0};
        const long factor = derivative_factor(exponents[m], d, lowered);
        if (cln::zerop(c[m]) || !factor) continue;
        const NodeId term = scaled(b.g, c[m] * Rational(factor), power(lowered));
        acc = sum(b.g, acc, product(b.g, b.g.load(static_cast<int>(k)), term));
      }
    }
    return acc;
  };
  std::vector<NodeId> d;
  for (const Exponent& e : derivative_indices(n, 2)) d.push_back(derivative(e));
  return finish(std::move(b), EmissionStrategy::Monomial, derivative({0, 0, 0}), d, n,
                {"// Orbit {orbit}: every stencil polynomial written out", {{"orbit", "0"}}});
}

TEST(StrategyBuilders, ANewStrategyFollowingTheRecipeIsExact) {
  const Derivation& a = fixture::derivation_of("zp");
  const ReferenceRegion& ref = a.structure.references[0];
  const int n = 2;
  const auto code = written_out_code(ref, n, a.properties.degree);
  ASSERT_TRUE(code);
  const Program& p = *code->program;
  std::mt19937_64 rng(11);
  auto rational = [&] {
    return Rational(static_cast<long>(rng() % 2001) - 1000) /
           Rational(static_cast<long>(rng() % 97 + 1));
  };
  for (int trial = 0; trial < 3; ++trial) {
    RatVec x(n), v(ref.basis.size());
    for (auto& xi : x) xi = rational();
    for (auto& vk : v) vk = rational();
    const auto values = evaluate_exactly(p.graph, x, v);
    // value, gradient, Hessian (0,0), (0,1), (1,1): the order of d[]
    std::vector<Rational> expected(6, 0);
    for (std::size_t k = 0; k < ref.basis.size(); ++k) {
      const Poly& q = ref.basis[k];
      const Rational terms[] = {q.eval(x),
                                q.derivative(0).eval(x),
                                q.derivative(1).eval(x),
                                q.derivative(0).derivative(0).eval(x),
                                q.derivative(0).derivative(1).eval(x),
                                q.derivative(1).derivative(1).eval(x)};
      for (int i = 0; i < 6; ++i) expected[i] = expected[i] + v[k] * terms[i];
    }
    EXPECT_EQ(values[p.blocks[0].outputs.at(0).second], expected[0]);
    for (int block = 1; block < 3; ++block)
      for (const auto& [index, node] : p.blocks[block].outputs)
        EXPECT_EQ(values[node], expected[1 + index]) << "d[" << index << "]";
  }
  const std::string text = CppPrinter().orbit_functions(*code, 0);
  EXPECT_EQ(text.rfind("// Orbit 0: every stencil polynomial written out\n", 0), 0u) << text;
  const auto horner = choose_orbit_code(ref, 0, n, a.properties.degree, EmissionStrategy::Horner);
  EXPECT_GT(code->gradient.total(), horner.gradient.total());
}

}  // namespace
}  // namespace boxgen::generator::strategies
