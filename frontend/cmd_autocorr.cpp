#include <fmt/core.h>

#include "frontend/commands.h"
#include "generator/autocorr.h"
#include "generator/error.h"

namespace boxgen::frontend {

int run_autocorr(const Common& c, const std::string& method) {
  const BoxSplineSpec spec = parse_spec(c.spec, c.lattice);
  Autocorrelation a;
  if (method == "refinement")
    a = autocorrelation_refinement(spec);
  else if (method == "continuity")
    a = autocorrelation_continuity(spec);
  else
    fail_input("unknown --method '" + method + "': expected refinement or continuity");
  if (c.json) {
    nlohmann::json samples = nlohmann::json::array();
    for (const auto& s : a.samples)
      samples.push_back({{"point", s.point}, {"value", to_string(s.value)}});
    print_json({{"method", method},
                {"integral_squared", to_string(a.integral_squared)},
                {"samples", samples}});
    return 0;
  }
  fmt::print("lattice samples of the doubled box spline of {} ({} method)\n", spec.name, method);
  fmt::print("  integral of (M^c)^2 = a(0) = {}\n", to_string(a.integral_squared));
  for (const auto& s : a.samples)
    fmt::print("  {:<16} {}\n", format_point(s.point), to_string(s.value));
  return 0;
}

}  // namespace boxgen::frontend
