#include <iostream>

#include "frontend/commands.h"

namespace boxgen::frontend {

nlohmann::json rational_list(const RatVec& v) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& x : v) out.push_back(to_string(x));
  return out;
}

std::string format_point(const IntVec& p) {
  std::string s = "(";
  for (size_t i = 0; i < p.size(); ++i) {
    if (i) s += ',';
    s += std::to_string(p[i]);
  }
  s += ')';
  return s;
}

void print_json(const nlohmann::json& j) { std::cout << j.dump(2) << '\n'; }

}  // namespace boxgen::frontend
