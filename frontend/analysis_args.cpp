#include "frontend/analysis_args.h"

#include <fmt/core.h>

#include <cmath>
#include <sstream>

#include "generator/error.h"

namespace boxgen::frontend {

analysis::Vec parse_direction(const std::string& text, int dimension, const std::string& what) {
  std::string t = text;
  for (char& ch : t)
    if (ch == ',') ch = ' ';
  std::istringstream is(t);
  std::vector<double> v;
  double x;
  while (is >> x) v.push_back(x);
  std::string rest;
  is.clear();
  if ((is >> rest) || static_cast<int>(v.size()) != dimension)
    fail_input(fmt::format("{} '{}' must be {} numbers such as {}", what, text.substr(0, 40),
                           dimension, dimension == 3 ? "1,1,1" : "1,1"));
  analysis::Vec d{0, 0, 0};
  double norm = 0;
  for (int i = 0; i < dimension; ++i) {
    if (!std::isfinite(v[i]))
      fail_input(fmt::format("{} '{}' has a non-finite entry", what, text.substr(0, 40)));
    d[i] = v[i];
    norm += v[i] * v[i];
  }
  if (norm == 0) fail_input(fmt::format("{} must not be the zero vector", what));
  return d;
}

std::vector<double> abscissae(const FrequencyOptions& o, bool log, double fallback_from,
                              double fallback_to, int fallback_steps, bool required) {
  const bool range = o.from || o.to || o.steps != 0;
  if (!o.w.empty() && range) fail_input("give either --w or --from/--to/--steps, not both");
  if (!o.w.empty()) {
    for (double w : o.w)
      if (!std::isfinite(w)) fail_input("--w values must be finite");
    if (log)
      for (double w : o.w)
        if (w <= 0) fail_input("--w values must be positive for a log-axis plot");
    return o.w;
  }
  if (!range && required) fail_input("give the abscissae: --w LIST or --from A --to B --steps K");
  const double from = o.from.value_or(fallback_from), to = o.to.value_or(fallback_to);
  const int steps = o.steps != 0 ? o.steps : fallback_steps;
  if (range && (!o.from || !o.to)) fail_input("--from and --to go together");
  if (!std::isfinite(from) || !std::isfinite(to)) fail_input("--from and --to must be finite");
  if (!(to > from))
    fail_input(
        fmt::format("empty or inverted range: --from {} --to {} (need from < to)", from, to));
  if (steps < 2 || steps > 100000)
    fail_input(fmt::format("--steps must be between 2 and 100000, got {}", steps));
  if (log && from <= 0) fail_input("--from must be positive for a log-axis plot");
  std::vector<double> out(steps);
  for (int i = 0; i < steps; ++i) {
    const double t = static_cast<double>(i) / (steps - 1);
    out[i] = log ? from * std::pow(to / from, t) : from + (to - from) * t;
  }
  out.back() = to;
  return out;
}

}  // namespace boxgen::frontend
