// Small text helpers shared by the code writers (emitter, polynomial_code): C++ literals and
// brace lists as they appear in emitted headers.
#pragma once
#include <fmt/format.h>

#include <string>
#include <vector>

#include "generator/rational.h"

namespace boxgen::generator::code {

// A double literal that round-trips (17 significant digits).
inline std::string literal(const Rational& r) { return fmt::format("{:.17g}", to_double(r)); }

inline std::string join(const std::vector<std::string>& parts, const char* sep = ", ") {
  std::string out;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (i) out += sep;
    out += parts[i];
  }
  return out;
}

template <class V>
std::string brace_list(const V& values) {
  std::vector<std::string> parts;
  for (const auto& v : values) parts.push_back(fmt::format("{}", v));
  return "{" + join(parts) + "}";
}

// "(a,b,c)" with exact rational entries, for comments.
inline std::string vertex_text(const RatVec& v) {
  std::vector<std::string> parts;
  for (const auto& x : v) parts.push_back(to_string(x));
  return "(" + join(parts, ",") + ")";
}

}  // namespace boxgen::generator::code
