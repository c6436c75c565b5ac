// Small text helpers shared by the code writers (the printers of
// generator/codegen/targets/target_printer.h, the emitter, polynomial_code): lists as they appear
// in emitted code. Literals are the printers'.
#pragma once
#include <fmt/format.h>

#include <string>
#include <vector>

#include "generator/rational.h"

namespace boxgen::generator::code {

inline std::string join(const std::vector<std::string>& parts, const char* sep = ", ") {
  std::string out;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (i) out += sep;
    out += parts[i];
  }
  return out;
}

// "1, -2, 3": the values as fmt prints them, comma-separated.
template <class V>
std::string list(const V& values) {
  std::vector<std::string> parts;
  for (const auto& v : values) parts.push_back(fmt::format("{}", v));
  return join(parts);
}

// "{1, -2, 3}": a C++ initialiser.
template <class V>
std::string brace_list(const V& values) {
  return "{" + list(values) + "}";
}

// "(a,b,c)" with exact rational entries, for comments.
inline std::string vertex_text(const RatVec& v) {
  std::vector<std::string> parts;
  for (const auto& x : v) parts.push_back(to_string(x));
  return "(" + join(parts, ",") + ")";
}

}  // namespace boxgen::generator::code
