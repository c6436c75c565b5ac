// Exact rational numbers (CLN) and small integer vectors: the number types of the generator.
#pragma once
#include <cln/integer.h>
#include <cln/rational.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace boxgen::generator {

using Rational = cln::cl_RA;
using Integer = cln::cl_I;
using RatVec = std::vector<Rational>;
using IntVec = std::vector<std::int64_t>;

// Parses "p", "p/q", "-1.25", "3e-2", "1.5E+3" exactly. Throws InputError naming `what`.
Rational parse_rational(std::string_view text, std::string_view what = "number");
// Parses a point "x y z" (blank or comma separated) of the given dimension.
RatVec parse_point(std::string_view text, int dimension, std::string_view what = "point");

std::string to_string(const Rational& r);  // "p/q" or "p"
double to_double(const Rational& r);
// The exact value of a finite double.
Rational exact_rational(double d);
Rational floor_rational(const Rational& r);  // as a rational integer
bool is_integer(const Rational& r);
std::int64_t floor_to_int64(const Rational& r);
Rational rational_from(std::int64_t value);
// p / q exactly (q != 0).
inline Rational fraction(long p, long q = 1) { return Rational(p) / Rational(q); }

RatVec to_ratvec(const IntVec& v);
Rational dot(const IntVec& a, const RatVec& b);
std::int64_t dot(const IntVec& a, const IntVec& b);

}  // namespace boxgen::generator
