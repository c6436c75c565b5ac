#include "generator/rational.h"

#include <optional>

#include <cln/integer_io.h>
#include <cln/rational_io.h>
#include <cln/real.h>

#include <cctype>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <sstream>

#include "generator/error.h"

namespace boxgen::generator {

namespace {

// What a message repeats of the user's text: at most 40 characters, control characters as '?',
// so an error stays one line whatever was typed.
std::string echo(std::string_view s) {
  std::string out;
  for (char c : s.substr(0, 40))
    out.push_back(std::isprint(static_cast<unsigned char>(c)) ? c : '?');
  if (s.size() > 40) out += "...";
  return out;
}

bool all_digits(std::string_view s) {
  if (s.empty()) return false;
  for (char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

Integer parse_digits(std::string_view s) {
  // Digit strings are validated by the caller; CLN parses arbitrary length exactly.
  return Integer(std::string(s).c_str());
}

}  // namespace

namespace {

// "p/q" (sign already removed); nullopt if it is not one.
std::optional<Rational> parse_fraction(std::string_view s, std::string_view text,
                                       std::string_view what) {
  const auto slash = s.find('/');
  const std::string_view num = s.substr(0, slash), den = s.substr(slash + 1);
  if (!all_digits(num) || !all_digits(den)) return std::nullopt;
  const Integer d = parse_digits(den);
  if (cln::zerop(d)) fail_input(std::string(what) + " '" + echo(text) + "' has a zero denominator");
  return Rational(parse_digits(num)) / Rational(d);
}

// The power of ten of an exponent "[+-]digits"; nullopt if it is not one.
std::optional<long> parse_exponent(std::string_view exponent, std::string_view text,
                                   std::string_view what) {
  bool negative = false;
  if (!exponent.empty() && (exponent.front() == '+' || exponent.front() == '-')) {
    negative = exponent.front() == '-';
    exponent.remove_prefix(1);
  }
  if (!all_digits(exponent) || exponent.size() > 4) return std::nullopt;
  const long e = std::stol(std::string(exponent));
  if (e > 400)
    fail_input(std::string(what) + " '" + echo(text) +
               "' has an exponent out of range (|e| <= 400)");
  return negative ? -e : e;
}

// "12", "1.5", ".5", "3e-2", "1.5E+3" (sign already removed), exactly; nullopt if it is none.
std::optional<Rational> parse_decimal(std::string_view s, std::string_view text,
                                      std::string_view what) {
  std::string_view mantissa = s, exponent;
  if (auto e = s.find_first_of("eE"); e != std::string_view::npos) {
    mantissa = s.substr(0, e);
    exponent = s.substr(e + 1);
    if (exponent.empty()) return std::nullopt;
  }
  std::string_view int_part = mantissa, frac_part;
  if (auto dot_pos = mantissa.find('.'); dot_pos != std::string_view::npos) {
    int_part = mantissa.substr(0, dot_pos);
    frac_part = mantissa.substr(dot_pos + 1);
  }
  if (int_part.empty() && frac_part.empty()) return std::nullopt;
  if (!int_part.empty() && !all_digits(int_part)) return std::nullopt;
  if (!frac_part.empty() && !all_digits(frac_part)) return std::nullopt;
  const std::string digits = std::string(int_part) + std::string(frac_part);
  const Rational value = Rational(parse_digits(digits.empty() ? "0" : digits));
  long scale = -static_cast<long>(frac_part.size());
  if (!exponent.empty()) {
    const auto e = parse_exponent(exponent, text, what);
    if (!e) return std::nullopt;
    scale += *e;
  }
  const Rational ten_power = cln::expt(Rational(10), static_cast<int>(scale < 0 ? -scale : scale));
  return scale < 0 ? value / ten_power : value * ten_power;
}

}  // namespace

Rational parse_rational(std::string_view text, std::string_view what) {
  std::string_view s = text;
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  const bool plausible = !s.empty() && s.size() <= 200;
  bool negative = false;
  if (plausible && (s.front() == '+' || s.front() == '-')) {
    negative = s.front() == '-';
    s.remove_prefix(1);
  }
  std::optional<Rational> value;
  if (plausible && !s.empty())
    value = s.find('/') != std::string_view::npos ? parse_fraction(s, text, what)
                                                  : parse_decimal(s, text, what);
  if (!value)
    fail_input(std::string("invalid ") + std::string(what) + " '" + echo(text) +
               "': expected an integer, a fraction p/q or a decimal such as -0.25");
  return negative ? Rational(-*value) : *value;
}

RatVec parse_point(std::string_view text, int dimension, std::string_view what) {
  RatVec out;
  std::string token;
  auto flush = [&] {
    if (!token.empty()) {
      out.push_back(parse_rational(token, "coordinate"));
      token.clear();
    }
  };
  for (char c : text) {
    if (std::isspace(static_cast<unsigned char>(c)) || c == ',')
      flush();
    else
      token.push_back(c);
  }
  flush();
  if (static_cast<int>(out.size()) != dimension)
    fail_input(std::string("invalid ") + std::string(what) + " '" + echo(text) + "': expected " +
               std::to_string(dimension) + " coordinates, got " + std::to_string(out.size()));
  return out;
}

std::string to_string(const Rational& r) {
  std::ostringstream os;
  cln::fprint(os, r);
  return os.str();
}

double to_double(const Rational& r) { return cln::double_approx(r); }

Rational exact_rational(double d) {
  int e = 0;
  const double f = std::frexp(d, &e);  // d = f 2^e, |f| in [0.5, 1): f 2^53 is an integer
  const Rational mantissa = Rational(static_cast<long long>(std::ldexp(f, 53)));
  return e >= 53 ? Rational(mantissa * cln::expt(Rational(2), e - 53))
                 : Rational(mantissa / cln::expt(Rational(2), 53 - e));
}

bool is_integer(const Rational& r) { return cln::denominator(r) == 1; }

Rational floor_rational(const Rational& r) { return Rational(cln::floor1(r)); }

std::int64_t floor_to_int64(const Rational& r) {
  Integer f = cln::floor1(r);
  if (cln::integer_length(f) > 62) fail_internal("coordinate out of 64-bit range");
  return cln::cl_I_to_Q(f);
}

Rational rational_from(std::int64_t value) { return Rational(static_cast<long long>(value)); }

RatVec to_ratvec(const IntVec& v) {
  RatVec out;
  out.reserve(v.size());
  for (auto x : v) out.push_back(rational_from(x));
  return out;
}

namespace {

__extension__ using Int128 = __int128;

// r = p/q (q > 0, lowest terms) with p and q fixnums, which fit in 64 bits.
bool small_parts(const Rational& r, std::int64_t& p, std::int64_t& q) {
  if (!r.pointer_p()) {  // an immediate: a fixnum integer
    p = cln::cl_I_to_Q(cln::numerator(r));
    q = 1;
    return true;
  }
  const Integer num = cln::numerator(r), den = cln::denominator(r);
  if (num.pointer_p() || den.pointer_p()) return false;
  p = cln::cl_I_to_Q(num);
  q = cln::cl_I_to_Q(den);
  return true;
}

// a.b in machine integers as p/q, or nullopt if anything could overflow.
std::optional<Rational> small_dot(const IntVec& a, const RatVec& b) {
  constexpr Int128 kLimit = Int128(1) << 100;
  Int128 p = 0;
  std::int64_t q = 1;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i] == 0) continue;
    std::int64_t n = 0, d = 1;
    if (!small_parts(b[i], n, d)) return std::nullopt;
    Int128 term = Int128(a[i]) * n;  // |a[i] n| < 2^126
    if (d != q) {
      const std::int64_t g = std::gcd(q, d);
      const Int128 scale_p = d / g, scale_term = q / g;
      const Int128 new_q = scale_term * d;
      if (new_q >= (Int128(1) << 62)) return std::nullopt;
      if (__builtin_mul_overflow(p, scale_p, &p)) return std::nullopt;
      if (__builtin_mul_overflow(term, scale_term, &term)) return std::nullopt;
      q = static_cast<std::int64_t>(new_q);
    }
    if (__builtin_add_overflow(p, term, &p)) return std::nullopt;
    if (p >= kLimit || p <= -kLimit) return std::nullopt;
  }
  if (p > INT64_MAX || p < -INT64_MAX) return std::nullopt;
  auto num = static_cast<std::int64_t>(p);
  const std::int64_t g = std::gcd(num, q);
  num /= g;
  q /= g;
  if (q == 1) return rational_from(num);
  return Rational(rational_from(num) / rational_from(q));  // reduces to lowest terms
}

}  // namespace

Rational dot(const IntVec& a, const RatVec& b) {
  if (auto fast = small_dot(a, b)) return *std::move(fast);
  Rational s = 0;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i] != 0) s = s + rational_from(a[i]) * b[i];
  return s;
}

std::int64_t dot(const IntVec& a, const IntVec& b) {
  std::int64_t s = 0;
  for (size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

}  // namespace boxgen::generator
