// The exact bridge between Poly (CLN) and GiNaC expressions: expected expressions are written
// out by hand in GiNaC, never produced by the bridge itself.
#include "generator/ginac_bridge.h"

#include <gtest/gtest.h>

#include "generator/error.h"

namespace boxgen::generator {
namespace {

GiNaC::ex parse(const std::string& text) {
  GiNaC::symtab table;
  for (const auto& s : coordinate_symbols(3)) table[s.get_name()] = s;
  table["w"] = GiNaC::symbol("w");
  GiNaC::parser reader(table);
  reader.strict = true;
  return reader(text);
}

// 3/7 x^2 y - 5 z + 1/2 + (2^100 + 1)/3 x y z^4, set coefficient by coefficient.
Poly sample_poly() {
  Poly p(3, 0);
  p.set_coefficient({2, 1, 0}, Rational(3) / 7);
  p.set_coefficient({0, 0, 1}, Rational(-5));
  p.set_coefficient({0, 0, 0}, Rational(1) / 2);
  p.set_coefficient({1, 1, 4}, (cln::expt_pos(Integer(2), 100) + 1) / Rational(3));
  return p;
}

TEST(GinacBridge, ToExpressionIsTheHandWrittenExpression) {
  const auto& v = coordinate_symbols(3);
  const GiNaC::numeric big = (GiNaC::numeric(2).power(100) + 1) / 3;
  const GiNaC::ex expected = GiNaC::numeric(3, 7) * GiNaC::pow(v[0], 2) * v[1] - 5 * v[2] +
                             GiNaC::numeric(1, 2) + big * v[0] * v[1] * GiNaC::pow(v[2], 4);
  EXPECT_TRUE((to_ex(sample_poly()) - expected).expand().is_zero()) << to_ex(sample_poly());
}

TEST(GinacBridge, ParsedTextBecomesTheExactPolynomial) {
  const Poly p =
      to_poly(parse("1/2 - 5*z + 3/7*x^2*y + (2^100+1)/3*x*y*z^4"), coordinate_symbols(3));
  EXPECT_EQ(p, sample_poly());
  // Products are expanded and like terms collected.
  const Poly q = to_poly(parse("(x+1)^2 - x^2 - 2*x"), coordinate_symbols(3));
  EXPECT_EQ(q, Poly::constant(3, 1));
}

TEST(GinacBridge, RoundTripIsExact) {
  EXPECT_EQ(to_poly(to_ex(sample_poly()), coordinate_symbols(3)), sample_poly());
  EXPECT_EQ(to_rational(to_numeric(Rational(-22) / 7)), Rational(-22) / 7);
  EXPECT_TRUE(to_poly(GiNaC::ex(0), coordinate_symbols(3)).is_zero());
}

TEST(GinacBridge, TwoDimensionalPolynomialsUseXAndY) {
  Poly p(2, 0);
  p.set_coefficient({1, 2, 0}, Rational(-1) / 3);
  const auto& v = coordinate_symbols(2);
  ASSERT_EQ(v.size(), 2u);
  EXPECT_TRUE((to_ex(p) + GiNaC::numeric(1, 3) * v[0] * GiNaC::pow(v[1], 2)).expand().is_zero());
  EXPECT_EQ(to_poly(to_ex(p), v), p);
}

TEST(GinacBridge, WhatIsNotARationalPolynomialIsRefused) {
  const auto& v = coordinate_symbols(3);
  for (const char* text : {"x*w", "x^(1/2)", "1/x", "sqrt(2)*x", "1.5*x"}) {
    SCOPED_TRACE(text);
    EXPECT_THROW(to_poly(parse(text), v), InputError);
  }
  EXPECT_THROW(to_rational(GiNaC::numeric(1.5)), InputError);
}

}  // namespace
}  // namespace boxgen::generator
