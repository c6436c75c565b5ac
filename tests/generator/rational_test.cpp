#include "generator/rational.h"

#include <gtest/gtest.h>

#include <string>

#include "generator/error.h"

namespace boxgen::generator {
namespace {

Rational frac(long p, long q) { return Rational(p) / Rational(q); }

void expect_parses_to(const std::string& text, const Rational& expected) {
  const Rational got = parse_rational(text);
  EXPECT_TRUE(got == expected) << "'" << text << "' gave " << to_string(got) << ", expected "
                               << to_string(expected);
}

void expect_rejected(const std::string& text) {
  try {
    parse_rational(text, "coordinate");
    ADD_FAILURE() << "'" << text << "' was accepted";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_FALSE(message.empty());
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_NE(message.find("coordinate"), std::string::npos)
        << message;  // names what was being read
  }
}

TEST(ParseRational, FractionsAndIntegers) {
  expect_parses_to("1/3", frac(1, 3));
  expect_parses_to("-4/6", frac(-2, 3));
  expect_parses_to("+2", Rational(2));
  expect_parses_to("0", Rational(0));
  expect_parses_to("  7 ", Rational(7));
  // Exact beyond 64 bits: 2^70 = 1180591620717411303424.
  expect_parses_to("1180591620717411303424", cln::expt(Rational(2), 70));
}

TEST(ParseRational, DecimalsAreExact) {
  expect_parses_to("-0.25", frac(-1, 4));
  expect_parses_to("1.5e-3", frac(3, 2000));
  expect_parses_to("1.5E+3", Rational(1500));
  expect_parses_to(".5", frac(1, 2));
  expect_parses_to("2.", Rational(2));
  expect_parses_to("0.1", frac(1, 10));  // not the binary double nearest 0.1
  expect_parses_to("3e2", Rational(300));
}

TEST(ParseRational, RoundTripsThroughToString) {
  for (const Rational& r :
       {frac(1, 3), frac(-7, 2), Rational(0), Rational(-12), frac(39559, 1064448)})
    EXPECT_TRUE(parse_rational(to_string(r)) == r) << to_string(r);
  EXPECT_EQ(to_string(frac(-2, 4)), "-1/2");
}

TEST(ParseRational, BadInputIsAnInputError) {
  for (const char* bad :
       {"abc", "1/0", "1..2", "",   "   ", "1e99999", "1/",  "/2",  "1/-2", "1.5/2",
        "--1", "+",   "e5",   "1e", "1e+", "0x10",    "1 2", "nan", "inf",  "1,5"})
    expect_rejected(bad);
}

TEST(ParseRational, ZeroDenominatorIsNamed) {
  try {
    parse_rational("1/0");
    ADD_FAILURE() << "1/0 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("zero denominator"), std::string::npos) << e.what();
  }
}

TEST(ParsePoint, BlankOrCommaSeparated) {
  const RatVec p = parse_point("1/3 -0.25 2", 3);
  ASSERT_EQ(p.size(), 3u);
  EXPECT_TRUE(p[0] == frac(1, 3));
  EXPECT_TRUE(p[1] == frac(-1, 4));
  EXPECT_TRUE(p[2] == Rational(2));

  const RatVec q = parse_point(" 0.5,1e-1 ", 2);
  ASSERT_EQ(q.size(), 2u);
  EXPECT_TRUE(q[0] == frac(1, 2));
  EXPECT_TRUE(q[1] == frac(1, 10));
}

TEST(ParsePoint, DimensionMismatchIsAnInputError) {
  EXPECT_THROW(parse_point("1 2", 3), InputError);
  EXPECT_THROW(parse_point("1 2 3", 2), InputError);
  EXPECT_THROW(parse_point("", 2), InputError);
  try {
    parse_point("1 2", 3);
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("expected 3 coordinates, got 2"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(ParsePoint, NonNumericCoordinateIsAnInputError) {
  EXPECT_THROW(parse_point("1 x 2", 3), InputError);
  EXPECT_THROW(parse_point("1 2 1/0", 3), InputError);
}

}  // namespace
}  // namespace boxgen::generator
